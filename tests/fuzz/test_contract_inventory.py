"""Every public surface has input-contract rows: the inventory read from the code against the rows.

See ``contract_inventory`` for how the inventory and the rows are gathered. A public name added
without rows (in any ``tests/fuzz/test_*.py`` or ``tests/cli/test_*.py`` with a
``contract_rows()``) fails :func:`test_every_public_surface_has_rows`.
"""

from __future__ import annotations

import pytest
from contract_inventory import (
    collect_rows,
    covered,
    inventory,
    problems,
    read_pending,
    resolve,
)


@pytest.fixture(scope="module")
def entries():
    return inventory()


@pytest.fixture(scope="module")
def rows():
    return collect_rows()


def test_every_public_surface_has_rows(entries, rows):
    found = problems(entries, rows, read_pending())
    assert not found, "\n".join(found)


def test_the_inventory_is_read_from_the_code(entries):
    """Functions, classes, methods, commands, flags and file formats are all there."""
    for name in ("ebantenna.device.plan.load_plan", "ebantenna.device.plan.Plan",
                 "ebantenna.ml.svc.SVC.fit", "cli:record", "cli:record --yes",
                 "cli:dataset --from-recordings", "file:manifest", "file:plan", "file:model"):
        assert name in entries, name
    assert resolve("SVC.fit", entries) == "ebantenna.ml.svc.SVC.fit"
    assert resolve("ml.SVC.fit", entries) == "ebantenna.ml.svc.SVC.fit"
    assert len(entries) > 800
    assert not any(name.endswith(("Error", "Warning")) for name in entries
                   if not name.startswith(("cli:", "file:")))


@pytest.mark.parametrize("surface", ["ebantenna.device.plan.load_plan", "file:manifest",
                                     "cli:record --yes",
                                     "ebantenna.study.recorded.assemble.assemble_dataset"])
def test_removing_one_surfaces_rows_makes_it_fail(entries, rows, surface):
    pending = read_pending()
    assert not problems(entries, rows, pending)
    without = {file: {name: ids for name, ids in table.items()
                      if resolve_or_none(name, entries) != surface}
               for file, table in rows.items()}
    found = problems(entries, without, pending)
    assert found == [f"{surface}: public, and no contract rows (add them in a "
                     "tests/fuzz/test_contract_*.py contract_rows())"]


def test_a_new_public_name_without_rows_fails(entries, rows):
    grown = {**entries, "ebantenna.signal.spectral.brand_new": set()}
    assert problems(grown, rows, read_pending()) == [
        "ebantenna.signal.spectral.brand_new: public, and no contract rows (add them in a "
        "tests/fuzz/test_contract_*.py contract_rows())"]


def test_the_pending_list_only_shrinks(entries, rows):
    """A pending surface that gets rows, or leaves the package, must leave the list."""
    done, _ = covered(entries, rows)
    some = sorted(done)[0]
    assert problems(entries, rows, read_pending() | {some}) == [
        f"{some}: has rows now; take it off contract_pending.txt"]
    assert problems(entries, rows, read_pending() | {"ebantenna.gone"}) == [
        "ebantenna.gone: listed in contract_pending.txt but no longer public"]


def resolve_or_none(name, entries):
    try:
        return resolve(name, entries)
    except KeyError:
        return None
