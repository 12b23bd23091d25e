"""Progress bars: the notebook bar only where ipywidgets can draw it, no warning anywhere."""

import subprocess
import sys
import textwrap

from unloaded_time import run

from ebantenna import _progress

# A Jupyter kernel without ipywidgets, as tqdm.auto detects one (ipykernel's shell module is
# loaded), in which ``import ipywidgets`` fails. Warnings are recorded, not raised: tqdm.auto
# catches the exception its own warning would raise and falls back silently.
FAKE_KERNEL = textwrap.dedent(
    """
    import importlib.util, sys, types, warnings
    caught = warnings.catch_warnings(record=True)
    seen = caught.__enter__()
    warnings.simplefilter("always")

    class ZMQInteractiveShell:
        config = {"IPKernelApp": {}}

    sys.modules["ipykernel.zmqshell"] = types.ModuleType("ipykernel.zmqshell")
    sys.modules["IPython"] = types.SimpleNamespace(get_ipython=lambda: ZMQInteractiveShell())
    # older tqdm (4.60, the floor) imports IPython.display before it looks for ipywidgets
    sys.modules["IPython.display"] = types.SimpleNamespace(display=lambda *a, **k: None)
    sys.modules["ipywidgets"] = None  # import ipywidgets -> ImportError
    real_find_spec = importlib.util.find_spec
    importlib.util.find_spec = lambda name, *a: (
        None if name == "ipywidgets" else real_find_spec(name, *a)
    )
    """
)


def _run(code: str) -> subprocess.CompletedProcess:
    # importing tqdm and the package is a second or two of CPU: 120 s of the child's own time
    # (waits for a CPU left out) is a hang, whatever the load
    return run(
        [sys.executable, "-c", FAKE_KERNEL + textwrap.dedent(code)],
        120, capture_output=True, text=True,
    )


def test_tqdm_auto_fails_in_a_kernel_without_ipywidgets():
    # the witness: the fake kernel is one in which tqdm.auto's bar says "IProgress not found",
    # as a warning (recent tqdm) or as an ImportError when the bar is made (tqdm 4.60, the floor)
    done = _run(
        """
        import tqdm.auto
        try:
            list(tqdm.auto.tqdm(range(2)))
        except ImportError as error:
            seen.append(types.SimpleNamespace(message=error))
        assert any('IProgress not found' in str(w.message) for w in seen), seen
        """
    )
    assert done.returncode == 0, done.stderr


def test_the_package_bar_is_plain_and_silent_there():
    done = _run(
        """
        from ebantenna._progress import progress
        bar = progress(range(3), enabled=True)
        assert list(bar) == [0, 1, 2]
        assert type(bar).__module__ == "tqdm.std", type(bar)
        assert not seen, [str(w.message) for w in seen]
        """
    )
    assert done.returncode == 0, done.stderr


def test_with_ipywidgets_the_automatic_choice(monkeypatch):
    import tqdm.auto
    import tqdm.std

    monkeypatch.setattr(_progress.importlib.util, "find_spec", lambda name, *a: object())
    assert _progress.bar_class() is tqdm.auto.tqdm
    monkeypatch.setattr(_progress.importlib.util, "find_spec", lambda name, *a: None)
    assert _progress.bar_class() is tqdm.std.tqdm
