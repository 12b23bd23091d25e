"""A recording session: every touch of a :class:`~ebantenna.device.plan.Plan`, saved as it is made.

For each touch the session checks the rig (the servo outputs switched off and read back, the
accelerometer's identity), runs the search of :func:`~ebantenna.device.pantilt.search_and_record`
(search, touch, stop, record, release) and saves the recording with its labels, the rig's settings,
the driver's fault counts, the timestamps' uncertainty and the release's outcome. A session lives
in one folder::

    DIR/session.json           the plan, the rig's settings and every saved touch (the manifest)
    DIR/recordings/*.npz       one recording per touch (ebantenna.recording.Recording files)

*Nothing twice, nothing lost.* A recording is written under a temporary name, flushed to disk and
renamed, and only then entered in the manifest, itself replaced whole the same way. A session
that stops, however it stops (Ctrl-C, SIGTERM, a power cut), is resumed by running it again on the
same folder: the touches in the manifest are kept (their checksums verified), a recording that
was renamed into place but not yet entered (the power failed between the two) is entered, and a
touch that was under way is made again from the start, its partial window never kept.

*Safety first.* The session stops, saying why and what to do, when the rig is unsafe: the servos
could not be released (:class:`UnsafeRigError`, ``servos_may_be_powered``), or the bus does not
answer. The reason is written into the manifest; the next run checks the rig before anything
else and goes on only when the servo outputs read back switched off.
"""

from __future__ import annotations

import datetime
import hashlib
import json
import logging
import os
import re
import tempfile
from dataclasses import asdict, dataclass
from pathlib import Path

from .._files import inside, read_document, require
from .._progress import progress
from .._tempfiles import TEMPORARY_PREFIX, process_running
from .._validate import check_bool, check_in_range, check_int, check_path, open_regular
from ..recording import Recording
from .i2c import I2CError
from .mpu6050 import MPU6050, ChipIdentityError
from .oe import OE_ONLY
from .pantilt import PanTilt, search_and_record
from .pca9685 import PCA9685
from .plan import Plan, Touch, plan_differences
from .safety import ReleaseError, signals_held
from .watchdog import StreamStalledError

__all__ = ["Connection", "RecordingSession", "UnsafeRigError", "NoContactError",
           "SESSION_FORMAT", "MANIFEST", "CUT_SUPPLY", "file_sha256", "write_atomic",
           "save_recording", "fallback_paths", "read_manifest", "MANIFEST_KEYS", "ENTRY_KEYS",
           "MAX_LOST", "UNRECORDED_MAX_LOST"]

log = logging.getLogger(__name__)

#: Format tag of a session's manifest.
SESSION_FORMAT = "ebantenna-session-1"
#: The manifest's file name in the session folder.
MANIFEST = "session.json"
#: The keys a manifest must hold, and those of each entry of its ``recordings``.
MANIFEST_KEYS = ("format", "plan", "rig", "search", "recordings")
ENTRY_KEYS = ("file", "sha256", "touch", "material", "contact", "repetition")
#: The session folder's lock file (the pid of the process recording into it).
LOCK = "session.lock"
#: Largest share of a recording's window that may be lost to bus faults before the touch is
#: made again: a limit on the share lost, not on the number of failures. A failed FIFO read
#: restarts the FIFO and loses what it held: on the simulated rig one costs 4 to 7 % of a
#: one-second window at 100 kHz (so a touch with one is sometimes made again), under 3 % at
#: 400 kHz, and two about twice that (measured in the user guide's "Recording your own data
#: set"). The default of :class:`RecordingSession` and of ``ebantenna record --max-lost``.
MAX_LOST = 0.06
#: The limit of a manifest written before the limit was kept in it (the default then).
UNRECORDED_MAX_LOST = 0.02
#: The name of a temporary file of :func:`write_atomic`: the prefix, the writer's process id,
#: a dash and the name of the file it will become.
_TEMPORARY = re.compile(re.escape(TEMPORARY_PREFIX) + r"(\d+)-(.+)")
#: What to do when the servos could not be released.
CUT_SUPPLY = ("switch off the servo supply (V+ of the PCA9685) now, check the I2C wiring and "
              "'i2cdetect -y N' (0x40 and 0x68 must answer), then run the same command again: "
              "the session resumes once the servo outputs read back switched off")
#: What to do when the bus does not answer.
CHECK_BUS = ("check the I2C wiring, the 3.3 V supply of both boards and 'i2cdetect -y N' "
             "(0x40 PCA9685, 0x68 MPU-6050), then run the same command again to resume")


class UnsafeRigError(OSError):
    """The rig is not safe to go on with; the message says why and what the operator should do.

    Attributes
    ----------
    servos_may_be_powered : bool
        Whether the servos could not be confirmed released.
    """

    def __init__(self, message: str, *, servos_may_be_powered: bool):
        super().__init__(message)
        self.servos_may_be_powered = servos_may_be_powered


class NoContactError(RuntimeError):
    """A search ended without a contact: the object is not where the plan puts it."""


@dataclass
class Connection:
    """An open rig: the bus and clock the drivers use, and optionally its OE line and the
    simulated rig behind it (for its fault counts).

    Attributes
    ----------
    bus : smbus2.SMBus or ebantenna.device.simulated.SimulatedBus
    clock : ebantenna.device.clock.SystemClock or ebantenna.device.clock.VirtualClock
    output_enable : ebantenna.device.oe.OutputEnable or None
    simulated : ebantenna.device.simulated.SimulatedRig or None
    """

    bus: object
    clock: object
    output_enable: object = None
    simulated: object = None

    def __post_init__(self):
        if not callable(getattr(self.bus, "read_byte_data", None)):
            raise TypeError(f"bus must be an open I2C bus, got {type(self.bus).__name__}")
        if not callable(getattr(self.clock, "monotonic", None)):
            raise TypeError(f"clock must be a clock (with monotonic()), got "
                            f"{type(self.clock).__name__}")

    def close(self) -> None:
        """Close the bus and the OE line."""
        self.bus.close()
        if self.output_enable is not None:
            self.output_enable.close()


def file_sha256(path) -> str:
    """SHA-256 (hex) of a regular file's bytes (a FIFO or a device is refused, not read)."""
    h = hashlib.sha256()
    with open_regular(path, "a recording") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def _fsync_dir(path: Path) -> None:
    try:
        fd = os.open(path, os.O_RDONLY)
    except OSError:  # a platform without directory handles: the rename is all there is
        return
    try:
        os.fsync(fd)
    except OSError:
        pass
    finally:
        os.close(fd)


def write_atomic(path, write) -> Path:
    """Write a file whole or not at all: ``write(tmp)`` fills a temporary file beside ``path``,
    which is flushed to disk and renamed over ``path`` (a reader sees the old file or the new
    one, never half of one, whenever the power fails)."""
    if not callable(write):
        raise TypeError(f"write must be callable (a temporary path) -> None, got "
                        f"{type(write).__name__}")
    path = Path(check_path("path", path))
    tmp = path.with_name(f"{TEMPORARY_PREFIX}{os.getpid()}-{path.name}")
    try:
        write(tmp)
        with open(tmp, "rb+") as f:
            os.fsync(f.fileno())
        os.replace(tmp, path)
    finally:
        tmp.unlink(missing_ok=True)
    _fsync_dir(path.parent)
    return path


def fallback_paths(name: str) -> list[Path]:
    """Where a recording goes when its own path cannot be written: the working directory, then
    the system's temporary folder, each under ``name`` with the process id (two runs never
    overwrite each other's fallback)."""
    stem = Path(check_path("name", name)).name.removesuffix(".npz")
    if not stem:
        raise ValueError(f"name must end in a file name, got {name!r}")
    unique = f"{stem}-{os.getpid()}.npz"
    return [Path.cwd() / unique, Path(tempfile.gettempdir()) / unique]


def save_recording(recording, path, *, fallback_name: str) -> tuple[Path | None, list[str]]:
    """Write ``recording`` atomically to ``path`` (None: straight to the fallbacks), else to the
    first of :func:`fallback_paths` that can be written.

    Returns the path written (None when nothing could be) and what failed on the way, one line
    per failed location; it never raises :class:`OSError` (an interrupt does go through: the
    caller decides what it means).
    """
    if not isinstance(recording, Recording):
        raise TypeError(f"recording must be a Recording, got {type(recording).__name__}")
    candidates = ([] if path is None else [Path(check_path("path", path))]) + fallback_paths(
        check_path("fallback_name", fallback_name))
    failures = []
    for candidate in candidates:
        try:
            target = candidate if candidate.suffix == ".npz" else candidate.with_name(
                candidate.name + ".npz")
            return write_atomic(target, recording.save), failures
        except (OSError, ValueError) as exc:
            failures.append(f"could not write {candidate} ({exc})")
            log.error("could not save the recording to %s: %s", candidate, exc)
    return None, failures


def remove_leftover_temporaries(folder: Path) -> None:
    """Remove the temporary files :func:`write_atomic` left in ``folder`` (not below it) when
    its process was stopped; a file of a process still running, or of any other name, stays."""
    for leftover in folder.glob(f"{TEMPORARY_PREFIX}*"):
        match = _TEMPORARY.fullmatch(leftover.name)
        if match is None or not leftover.is_file() or process_running(int(match.group(1))):
            continue
        log.info("removing %s, left by an interrupted run", leftover)
        leftover.unlink(missing_ok=True)


def _check_session_folder(directory: Path) -> None:
    """Refuse a folder that is neither new, empty, nor a session's (see
    :meth:`~RecordingSession.open`)."""
    if not directory.exists():
        return
    if not directory.is_dir():
        raise NotADirectoryError(f"directory {directory} is not a folder")
    if (directory / MANIFEST).exists():
        return
    foreign = []
    for entry in directory.iterdir():
        if _TEMPORARY.fullmatch(entry.name) or entry.name == LOCK:
            continue
        if entry.name == "recordings" and entry.is_dir() and not entry.is_symlink() and all(
                _TEMPORARY.fullmatch(e.name) for e in entry.iterdir()):
            continue  # made by a session stopped before its manifest was first written
        foreign.append(entry.name)
    if foreign:
        shown = ", ".join(sorted(foreign)[:3]) + (", ..." if len(foreign) > 3 else "")
        raise FileExistsError(f"directory {directory} holds files that are not a recording "
                              f"session's ({shown}) and no {MANIFEST}: give a new or empty "
                              "folder for the session")


def _now() -> str:
    return datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds")


class RecordingSession:
    """Make, save and resume the touches of a plan in a session folder.

    Parameters
    ----------
    directory : path
        The session's folder (created if missing).
    plan : Plan
        The touches. A folder that holds a session of another plan is refused.
    connect : callable
        ``connect(touch, attempt)`` returns an open :class:`Connection` for one attempt (from 1)
        at a touch; the session closes it after the attempt.
    rig : dict
        JSON description of the rig (bus, simulated or not, scene, faults), stored in the manifest.
    max_lost : float
        Largest share of a recording's window that may be missing (samples lost to bus faults),
        in [0, 1). A touch that loses more is made again. Default :data:`MAX_LOST` (0.06), a
        limit on the share lost: one failed FIFO read costs 4 to 7 % of a one-second window at
        100 kHz, under 3 % at 400 kHz, and two about twice that.
    attempts : int
        Tries of a touch whose recording lost too much, >= 1. Default 5.
    say : callable, optional
        ``say(text)`` tells the operator what happens (default: the log).
    confirm : callable, optional
        ``confirm(text)`` waits for the operator to place the object as ``text`` asks (on the
        real rig); None goes on at once.
    show_progress : bool, optional
        Progress bar over the touches (default: on a terminal).
    """

    def __init__(self, directory, plan: Plan, connect, *, rig: dict | None = None,
                 max_lost: float = MAX_LOST, attempts: int = 5, say=None, confirm=None,
                 show_progress=None):
        if not isinstance(plan, Plan):
            raise TypeError(f"plan must be a Plan, got {type(plan).__name__}")
        if not callable(connect):
            raise TypeError(f"connect must be callable, got {type(connect).__name__}")
        if not isinstance(directory, (str, os.PathLike)):
            raise TypeError(f"directory must be a path, got {type(directory).__name__}")
        if os.fspath(directory) in ("", b""):
            raise ValueError("directory must name the session folder, got an empty path (it "
                             "would record into the working directory)")
        self.directory = Path(directory)
        self.plan, self.connect = plan, connect
        self.rig = json.loads(json.dumps(rig or {}))
        self.max_lost = check_in_range("max_lost", max_lost, 0.0, 1.0, low_inclusive=True)
        self.attempts = check_int("attempts", attempts, minimum=1)
        self.say = say or log.info
        self.confirm = confirm
        self.show_progress = show_progress
        self.config = plan.search_config()
        self.manifest = None
        #: Set when the servos of this run could not be confirmed released.
        self.servos_may_be_powered = False

    @property
    def manifest_path(self) -> Path:
        """The manifest's path."""
        return self.directory / MANIFEST

    # -- the manifest ----------------------------------------------------------------------
    def _new_manifest(self) -> dict:
        return {"format": SESSION_FORMAT, "plan": self.plan.to_dict(), "rig": self.rig,
                "max_lost": self.max_lost,
                "search": _search_settings(self.config), "created": _now(), "unsafe": None,
                "recordings": {}, "retakes": []}

    def _save_manifest(self) -> None:
        text = json.dumps(self.manifest, indent=1)
        write_atomic(self.manifest_path, lambda tmp: tmp.write_text(text, encoding="utf-8"))

    def open(self) -> dict:
        """Load (or start) the manifest, verify what it lists, enter recordings saved but not yet
        listed, and remove temporary files a power cut left; returns the manifest.

        Only what the session writes is ever removed: temporary files of :func:`write_atomic`
        (named ``.ebantenna-tmp<pid>-<name>``, of a process no longer running) in the two
        folders it writes them to, never elsewhere. A folder that holds other files and no
        manifest is refused: it is not a session folder, and the session would mix its files
        with the user's.
        """
        _check_session_folder(self.directory)
        (self.directory / "recordings").mkdir(parents=True, exist_ok=True)
        self._lock()
        for folder in (self.directory, self.directory / "recordings"):
            remove_leftover_temporaries(folder)
        if not os.path.lexists(self.manifest_path):
            self.manifest = self._new_manifest()
            self._save_manifest()
            return self.manifest
        inside(self.directory, MANIFEST, str(self.manifest_path))  # no link out of the folder
        self.manifest = read_manifest(self.manifest_path)
        if self.manifest["plan"] != self.plan.to_dict():
            self.release()
            differs = "; ".join(plan_differences(self.manifest["plan"], self.plan.to_dict()))
            raise ValueError(f"{self.directory} holds a session of another plan "
                             f"({self.manifest['plan']['name']!r}), which differs in {differs}; "
                             "give a new folder, or the same plan to resume it")
        self._check_same_settings()
        self._verify_listed()
        self._adopt_unlisted()
        return self.manifest

    def _check_same_settings(self) -> None:
        """Refuse to resume with other settings than the session was started with: its
        recordings and its manifest would describe two runs as one."""
        was = {**self.manifest["rig"],
               "max_lost": self.manifest.get("max_lost", UNRECORDED_MAX_LOST)}
        now = {**self.rig, "max_lost": self.max_lost}
        changed = sorted(k for k in set(was) | set(now) if was.get(k) != now.get(k))
        if changed:
            self.release()
            raise ValueError(
                f"{self.directory} holds a session started with other settings: "
                + "; ".join(f"{k} was {was.get(k)!r}, now {now.get(k)!r}" for k in changed)
                + ". Resume with the same settings, or record into a new folder")

    # -- the lock ----------------------------------------------------------------------------
    @property
    def lock_path(self) -> Path:
        """The lock file: it holds the pid of the process writing the session."""
        return self.directory / LOCK

    def _lock(self) -> None:
        """Take the session folder for this process; refuse while another live process holds
        it (two writers would drive one rig and mix their touches). A lock left by a process
        that no longer runs (power cut, SIGKILL) is taken over."""
        for _ in range(2):
            try:
                fd = os.open(self.lock_path, os.O_CREAT | os.O_EXCL | os.O_WRONLY, 0o644)
            except FileExistsError:
                try:
                    holder = int(self.lock_path.read_text().strip() or 0)
                except (OSError, ValueError):
                    holder = 0
                if holder == os.getpid():
                    return
                if holder > 0 and process_running(holder):
                    raise ValueError(f"{self.directory} is being recorded by another process "
                                     f"(pid {holder}, its lock {self.lock_path}); wait for it "
                                     "to end, or stop it, before running this session") from None
                self.lock_path.unlink(missing_ok=True)  # its writer no longer runs
                continue
            with os.fdopen(fd, "w") as f:
                f.write(f"{os.getpid()}\n")
            return

    def release(self) -> None:
        """Give the session folder up (the lock file is removed if this process holds it)."""
        try:
            if int(self.lock_path.read_text().strip() or 0) == os.getpid():
                self.lock_path.unlink()
        except (OSError, ValueError):
            pass

    def _verify_listed(self) -> None:
        where = str(self.manifest_path)
        for key, entry in list(self.manifest["recordings"].items()):
            path = inside(self.directory, entry["file"], where)
            if not os.path.lexists(path):
                log.warning("%s is listed but missing: touch %s will be made again", path, key)
                del self.manifest["recordings"][key]
            elif file_sha256(path) != entry["sha256"]:
                raise ValueError(f"{path}: checksum mismatch, the file was changed or damaged "
                                 f"since it was recorded; move it away and run again to record "
                                 f"touch {key} again")
        self._save_manifest()

    def _adopt_unlisted(self) -> None:
        """Enter recordings renamed into place whose manifest entry the power cut prevented."""
        listed = {e["file"] for e in self.manifest["recordings"].values()}
        for touch in self.plan:
            name = _file_name(touch)
            path = inside(self.directory, name, str(self.manifest_path))
            if name in listed or not os.path.lexists(path):
                continue
            try:
                rec = Recording.load(path)
            except ValueError as exc:
                log.warning("%s is damaged (%s): touch %s will be made again", path, exc,
                            touch.key)
                path.rename(path.with_suffix(".damaged"))
                continue
            if rec.metadata.get("touch_key") != touch.key:
                raise ValueError(f"{path} holds touch {rec.metadata.get('touch_key')!r}, not "
                                 f"{touch.key!r}: it belongs to another session")
            self.manifest["recordings"][touch.key] = _entry(touch, name, path, rec)
            log.info("entered %s, saved before the session stopped", path)
        self._save_manifest()

    # -- running -----------------------------------------------------------------------------
    def remaining(self) -> list[Touch]:
        """The touches not yet saved, in plan order."""
        done = self.manifest["recordings"]
        return [t for t in self.plan if t.key not in done]

    def run(self) -> dict:
        """Make every remaining touch; returns the manifest.

        Raises
        ------
        UnsafeRigError
            The rig is unsafe (servos not released, bus dead); the manifest says why.
        NoContactError
            A search found nothing: the object is not where the plan puts it.
        """
        if self.manifest is None:
            self.open()
        self._check_after_stop()
        todo = self.remaining()
        done = len(self.plan) - len(todo)
        if done:
            self.say(f"resuming: {done} of {len(self.plan)} touches already saved")
        bar = progress(total=len(self.plan), initial=done, desc="record",
                       enabled=self.show_progress)
        previous = None
        try:
            for touch in todo:
                self._place(touch, previous)
                self._record(touch)
                previous = touch
                bar.update()
        finally:
            bar.close()
            self.release()
        self.manifest["finished"] = _now()
        self._save_manifest()
        return self.manifest

    def _place(self, touch: Touch, previous: Touch | None) -> None:
        """Tell the operator what to place where, when it changes."""
        where = (f"place {touch.material} so that the probe touches it "
                 f"{100 * touch.contact:.1f} cm from the hinge")
        if previous is None or (previous.material, previous.contact) != (touch.material,
                                                                          touch.contact):
            self.say(where)
            if self.confirm is not None:
                self.confirm(where)

    def _record(self, touch: Touch) -> None:
        """One touch: made up to ``attempts`` times until its window is whole enough, saved."""
        n = len(self.plan)
        for attempt in range(1, self.attempts + 1):
            self.say(f"touch {touch.index + 1}/{n} ({touch.key}), attempt {attempt}: searching")
            result, conn = self._touch(touch, attempt)
            rec = result.recording
            lost = rec.metadata["samples_lost"] / (rec.n_samples + rec.metadata["samples_lost"])
            if lost <= self.max_lost or attempt == self.attempts:
                break
            self.manifest["retakes"].append({"touch": touch.key, "attempt": attempt,
                                             "samples_lost_fraction": lost, "at": _now()})
            self._save_manifest()
            self.say(f"touch {touch.key}: {lost:.1%} of the window lost to bus faults; again")
        if lost > self.max_lost:  # the last attempt is a retake too: the manifest lists them all
            self.manifest["retakes"].append({"touch": touch.key, "attempt": attempt,
                                             "samples_lost_fraction": lost, "at": _now()})
            self._save_manifest()
            raise UnsafeRigError(
                f"touch {touch.key}: every one of {self.attempts} attempts lost more than "
                f"{self.max_lost:.0%} of its window to bus faults; {CHECK_BUS}",
                servos_may_be_powered=False)
        self._save(touch, self._labelled(touch, result, conn))
        self.say(f"touch {touch.key}: saved ({rec.n_samples} samples, servos released)")
        for warning in result.warnings():  # kept: the operator decides
            self.say(f"touch {touch.key}: warning: {warning}")

    def _touch(self, touch: Touch, attempt: int):
        """Check the rig and run one search; returns the result and the connection used."""
        conn = _connection(self.connect(touch, attempt))
        try:
            unit, mpu = self._checked_rig(conn)
            try:
                result = search_and_record(mpu, unit, self.config,
                                           labels=touch.labels(self.plan.probe_length),
                                           output_enable=conn.output_enable)
            except ReleaseError as exc:
                self._unreleased(touch, exc)
            except StreamStalledError as exc:
                released = _servos_off(unit, conn)
                self._stop_unsafe(f"touch {touch.key}: the accelerometer stopped producing "
                                  f"({exc}); " + (CHECK_BUS if released else _cut_supply(conn)),
                                  not released)
            except BaseException as exc:  # an interrupt, any error: are the servos off?
                if not _servos_off(unit, conn):
                    self.servos_may_be_powered = True
                    self.mark_unsafe(f"touch {touch.key}: stopped ({describe_stop(exc)}) with "
                                     f"the servos not confirmed released; {_cut_supply(conn)}")
                raise
        finally:
            if not (conn.output_enable is not None and conn.output_enable.disabled):
                conn.close()  # an OE line driven high is kept: closed, it would float low
            else:
                conn.bus.close()
        if not result.contact_detected:
            raise NoContactError(
                f"touch {touch.key}: no contact within {self.config.max_search_time:g} s: put "
                f"{touch.material} in the probe's sweep {100 * touch.contact:.1f} cm from the "
                "hinge and run the same command again to resume")
        return result, conn

    def _checked_rig(self, conn: Connection):
        """Switch the servo outputs off and read them back, check the accelerometer.

        A rig that does not answer before its servo outputs are read back off may have them
        powered (exit 3); an accelerometer that does not answer after that is a stop with the
        servos known off (exit 2)."""
        try:
            unit = PanTilt(PCA9685(conn.bus, clock=conn.clock))
            unit.initialize()  # the outputs off before anything else
        except (I2CError, ChipIdentityError) as exc:
            self._stop_unsafe(f"the rig does not answer on the bus ({exc}); the servos may "
                              f"still be powered: {CUT_SUPPLY}", True)
        if unit.pca.pulse(0) or unit.pca.pulse(1):
            self._stop_unsafe("the servo outputs read back ON after being switched off; "
                              + CUT_SUPPLY, True)
        try:
            mpu = MPU6050(conn.bus, clock=conn.clock)
            mpu.initialize()
        except (I2CError, ChipIdentityError) as exc:
            self._stop_unsafe(f"the accelerometer does not answer ({exc}); the servo outputs "
                              f"read back off: {CHECK_BUS}", False)
        return unit, mpu

    def _unreleased(self, touch: Touch, exc: ReleaseError) -> None:
        """The release failed: keep the finished recording (first, before anything else that
        can fail; elsewhere when the session folder cannot be written), then stop."""
        self.servos_may_be_powered = True
        kept = ""
        with signals_held():  # the recording saved and the session marked, whatever arrives
            if exc.result is not None and exc.result.recording is not None:
                rec = self._labelled(touch, exc.result, None)
                try:
                    self._save(touch, rec)
                except OSError as error:

                    saved, _ = save_recording(
                        rec, None, fallback_name="record-" + touch.key.replace("/", "_"))
                    kept = (f" The recording could not be saved in the session ({error}); "
                            + (f"it was saved to {saved}." if saved else "it was lost."))
            why = (f"touch {touch.key}: the servos could not be released ({exc}); "
                   + CUT_SUPPLY + kept)
            if not self.mark_unsafe(why):
                why += f" ({self.manifest_path} could not be written)"
        raise UnsafeRigError(why, servos_may_be_powered=True)

    def mark_unsafe(self, why: str, powered: bool = True) -> bool:
        """Write ``why`` into the manifest's ``unsafe`` entry, so that the next run checks the
        rig first; returns whether the manifest could be written (a full disk or a removed
        folder is logged, never raised: the operator's instruction matters more)."""
        if not isinstance(why, str) or not why.strip():
            raise ValueError(f"why must be a non-empty str (what the operator reads), got {why!r}")
        powered = check_bool("powered", powered)
        self.servos_may_be_powered |= powered
        if self.manifest is None:
            return False
        self.manifest["unsafe"] = {"reason": why, "servos_may_be_powered": powered, "at": _now()}
        try:
            self._save_manifest()
        except OSError as exc:
            log.error("could not write %s (%s): the next run will not be warned",
                      self.manifest_path, exc)
            return False
        return True

    def _stop_unsafe(self, why: str, powered: bool) -> None:
        if not self.mark_unsafe(why, powered):
            why += f" ({self.manifest_path} could not be written)"
        raise UnsafeRigError(why, servos_may_be_powered=powered)

    def _check_after_stop(self) -> None:
        """After a stop on an unsafe rig: go on only if the rig now checks out."""
        unsafe = self.manifest.get("unsafe")
        if not unsafe:
            return
        self.say(f"the last run stopped: {unsafe['reason']}; checking the rig first")
        todo = self.remaining()
        conn = _connection(self.connect(todo[0] if todo else self.plan[0], 0))
        try:
            self._checked_rig(conn)
        finally:
            conn.close()
        self.say("the rig checks out: servo outputs switched off, accelerometer answering")
        self.manifest["unsafe"] = None
        self._save_manifest()

    def _labelled(self, touch: Touch, result, conn: Connection | None) -> Recording:
        """The touch's recording with the session's labels and the rig's account."""
        rec = result.recording
        meta = dict(rec.metadata)
        meta.update(touch.labels(self.plan.probe_length))
        meta.update({"plan": self.plan.name, "recorded_at": _now(), "rig": self.rig,
                     "search": _search_settings(self.config),
                     "release": {"servos_released": result.servos_released,
                                 "by": result.servos_released_by,
                                 "servos_stopped": result.servos_stopped},
                     "fault_counts": _fault_counts(result, conn)})
        return Recording(rec.t, rec.ax, rec.az, rec.fs, meta)

    def _save(self, touch: Touch, rec: Recording) -> None:
        """Write the recording whole, then enter it in the manifest."""
        name = _file_name(touch)
        path = write_atomic(self.directory / name, rec.save)
        self.manifest["recordings"][touch.key] = _entry(touch, name, path, rec)
        self._save_manifest()


def _servos_off(unit, conn: Connection) -> bool:
    """Whether the servo outputs last read back off over I2C. The OE pin held high does not
    count: it holds them off only while the program runs
    (:data:`~ebantenna.device.oe.OE_ONLY`)."""
    return bool(unit.released)


def _cut_supply(conn: Connection) -> str:
    """The instruction to cut the servo supply, saying first when the OE pin holds the outputs
    off for now."""
    oe = conn.output_enable
    return (f"{OE_ONLY}; {CUT_SUPPLY}" if oe is not None and oe.disabled else CUT_SUPPLY)


def describe_stop(exc: BaseException) -> str:
    """One line for what stopped a run: the signal's name, or the error's text."""
    signum = getattr(exc, "signum", None)
    if signum is not None:
        import signal

        return f"interrupted by {signal.Signals(signum).name}"
    if isinstance(exc, KeyboardInterrupt):
        return "interrupted by SIGINT"
    return " ".join(str(exc).splitlines()) or type(exc).__name__


def _connection(conn) -> Connection:
    """``conn``, returned by the session's ``connect``, if it is a :class:`Connection`."""
    if not isinstance(conn, Connection):
        raise TypeError(f"connect must return a Connection, got {type(conn).__name__}")
    return conn


def _file_name(touch: Touch) -> str:
    return (f"recordings/t{touch.index:05d}-{touch.material}-"
            f"{1000 * touch.contact:.1f}mm-r{touch.repetition}.npz")


def _entry(touch: Touch, name: str, path: Path, rec: Recording) -> dict:
    meta = rec.metadata
    return {"file": name, "sha256": file_sha256(path), "touch": touch.index,
            "material": touch.material, "contact": touch.contact, "repetition": touch.repetition,
            "samples": rec.n_samples, "fs_hz": rec.fs, "samples_lost": meta.get("samples_lost"),
            "timestamp_uncertainty_s": meta.get("timestamp_uncertainty_s"),
            "servos_released": meta.get("release", {}).get("servos_released"),
            "recorded_at": meta.get("recorded_at")}


def _fault_counts(result, conn: Connection | None) -> dict:
    stream = result.stream
    counts = {"i2c_retries": result.i2c_retries, "samples_lost": result.samples_lost,
              "stream_samples_lost": result.stream_samples_lost,
              "fifo_restarts": stream.get("fifo_restarts", 0),
              "fifo_overflows": stream.get("fifo_overflows", 0),
              "fifo_counts_rejected": stream.get("fifo_counts_rejected", 0),
              "fifo_resets_unconfirmed": stream.get("fifo_resets_unconfirmed", 0),
              "faults": len(stream.get("faults", []))}
    if conn is not None and conn.simulated is not None:
        counts["i2c_errors_injected"] = conn.simulated.bus.errors_injected
    return counts


def _search_settings(config) -> dict:
    return json.loads(json.dumps(asdict(config)))


def read_manifest(path) -> dict:
    """Read a session's manifest (``DIR/session.json``), every key it must hold checked.

    The manifest must be a regular file of at most 64 MiB of JSON nested at most 100 levels
    deep, holding
    :data:`MANIFEST_KEYS`; its plan must be a valid plan with every key of
    :meth:`~ebantenna.device.plan.Plan.to_dict`, its search the plan's; each entry of
    ``recordings`` must be a touch of the plan, under the touch's key, holding
    ``ENTRY_KEYS`` that agree with the touch, and naming the touch's own file inside the
    session folder (so no two entries name one file, and no entry a file elsewhere).

    Raises
    ------
    FileNotFoundError
        If there is no such file.
    ValueError
        Naming the file and the key at fault.
    """
    path = Path(check_path("path", path))
    where = str(path)
    manifest = read_document(path, "a session manifest")
    if not isinstance(manifest, dict) or manifest.get("format") != SESSION_FORMAT:
        raise ValueError(f"{path} is not a session manifest of format {SESSION_FORMAT!r}")
    require(manifest, MANIFEST_KEYS, where)
    plan = Plan.from_dict(manifest["plan"], f"{where}: plan", complete=True)
    for key in ("rig", "search", "recordings"):
        if not isinstance(manifest[key], dict):
            raise ValueError(f"{where}: {key} must be a table (a JSON object), got "
                             f"{type(manifest[key]).__name__}")
    if manifest["search"] != _search_settings(plan.search_config()):
        raise ValueError(f"{where}: search differs from the settings of the plan's search "
                         "(the manifest was edited)")
    for key in ("retakes",):
        if not isinstance(manifest.get(key, []), list):
            raise ValueError(f"{where}: {key} must be a list")
    unsafe = manifest.get("unsafe")
    if unsafe is not None and not (isinstance(unsafe, dict)
                                   and isinstance(unsafe.get("reason"), str)):
        raise ValueError(f"{where}: unsafe must be null or a table with a 'reason'")
    touches = {t.key: t for t in plan} if manifest["recordings"] else {}
    for key, entry in manifest["recordings"].items():
        _check_entry(where, key, entry, touches.get(key))
    return manifest


def _check_entry(where: str, key: str, entry, touch: Touch | None) -> None:
    """Raise unless ``entry`` is the manifest entry of ``touch`` (a touch of the plan)."""
    if touch is None:
        raise ValueError(f"{where}: recordings holds an entry {key!r:.80} for a touch the plan "
                         "does not have")
    require(entry, ENTRY_KEYS, f"{where}: recordings[{key!r}]")
    expected = _file_name(touch)
    if entry["file"] != expected:
        raise ValueError(f"{where}: recordings[{key!r}] names the file {entry['file']!r:.100}, "
                         f"not the touch's own {expected!r}")
    sha = entry["sha256"]
    if not (isinstance(sha, str) and len(sha) == 64
            and all(c in "0123456789abcdef" for c in sha)):
        raise ValueError(f"{where}: recordings[{key!r}]: sha256 must be 64 hex digits, got "
                         f"{sha!r:.80}")
    labels = {"touch": touch.index, "material": touch.material, "contact": touch.contact,
              "repetition": touch.repetition}
    for name, value in labels.items():
        given = entry[name]
        if type(given) is not type(value) or given != value:
            raise ValueError(f"{where}: recordings[{key!r}]: {name} is {given!r:.60}, the "
                             f"plan's touch has {value!r}")
