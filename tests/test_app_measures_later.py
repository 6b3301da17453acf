"""A molecule's shape shows before its measures: the info dock says they are being computed,
then its pockets layer and measures fill in; a result for an older dataset is dropped."""

from __future__ import annotations

import threading
from pathlib import Path

import numpy as np
import pytest
from conftest import BUILD_TIMEOUT_MS, image_contrast, wait_for_topology

from app.info_panel import MEASURING
from app.inspect_panel import POCKETS_PENDING
from tests.molecule_reference import shared_molecule
from tests.reference import DATA_ABSENT

PDB = shared_molecule("1A8O.pdb")
MOLECULES = Path(__file__).parent / "data" / "molecules"
RELEASE_TIMEOUT_S = 60
MIN_CONTRAST = 5.0
pytestmark = pytest.mark.gui


@pytest.fixture(autouse=True)
def private_cache(tmp_path, monkeypatch):
    """Each test starts with an empty table cache."""
    monkeypatch.setenv("ALPHASCOOP_CACHE_DIR", str(tmp_path / "cache"))


def hold(monkeypatch, name: str, cancellable: bool = True):
    """Make app.worker's `name` (with_measures or with_topology) wait until the returned
    event is set; its calls are recorded as (dataset, result) in the event's `calls`. Not
    `cancellable`: the held call ignores Cancel (its result still comes back, stale)."""
    import app.worker

    release = threading.Event()
    release.calls = []
    real = getattr(app.worker, name)

    def held(dataset, check=None):
        assert release.wait(RELEASE_TIMEOUT_S), f"the test never released {name}"
        result = real(dataset, check if cancellable else None)
        release.calls.append((dataset, result))
        return result

    monkeypatch.setattr(app.worker, name, held)
    return release


@pytest.fixture
def held_measures(monkeypatch):
    """A molecule's measures wait until the test sets the returned event."""
    release = hold(monkeypatch, "with_measures")
    yield release
    release.set()  # never leave a worker thread waiting


def open_table(qtbot, window, path) -> None:
    """Open path and wait only for its first frame (the table), not for what follows."""
    with qtbot.waitSignal(window.model.datasetChanged, timeout=BUILD_TIMEOUT_MS):
        window.open_path(path)


def wait_for_measures(qtbot, window) -> None:
    """Wait until the shown molecule's measures have arrived."""
    qtbot.waitUntil(lambda: window.model.dataset.molecule is not None, timeout=BUILD_TIMEOUT_MS)


@pytest.mark.skipif(PDB is None, reason=DATA_ABSENT)
def test_first_frame_before_the_measures(window, qtbot, held_measures):
    open_table(qtbot, window, PDB)
    ds = window.model.dataset
    assert ds.is_molecule and ds.molecule is None and ds.probe == 1.4
    assert window.measures.is_busy()
    scene = window.scene
    assert {"balls", "cavities"} <= set(scene.layers) and "pockets" not in scene.layers
    assert scene.layers["balls"].actor.GetVisibility()
    balls = scene.layers["balls"]
    assert balls.outer is None  # every ball may show while the exposed ones are unknown
    assert scene.seen.balls is balls.mesh  # (of those, the ones the view shows are drawn)
    scene.plotter.render()
    qtbot.wait(50)
    assert image_contrast(scene.plotter.screenshot(return_img=True)) > MIN_CONTRAST
    assert MEASURING in window.info_panel.data.text()
    assert "van der Waals radii (Bondi) + probe 1.4 Å" in window.info_panel.data.text()
    assert window.inspect_panel.fields["pocket"].text() == ""
    window.inspector.inspect_vertices(ds.ac.simplices(3)[0])
    assert window.inspect_panel.fields["pocket"].text() == POCKETS_PENDING  # not "no pocket"
    wait_for_topology(qtbot, window)  # the topology does not wait for the measures
    assert window.model.dataset.molecule is None and window.measures.is_busy()
    assert MEASURING in window.info_panel.data.text()
    with qtbot.waitSignal(window.model.measuresChanged, timeout=BUILD_TIMEOUT_MS):
        held_measures.set()
    m = window.model.dataset.molecule
    assert m.atoms == 556 and m.surface_area == pytest.approx(4668.88, abs=0.01)
    text = window.info_panel.data.text()
    assert MEASURING not in text and "4,668.88 Å²" in text and "2 cavities" in text
    assert window.model.dataset.has_topology  # the measures kept the topology
    assert scene.seen.balls is balls.outer  # now only the balls seen from outside (and of
    assert balls.outer.n_points < balls.mesh.n_points  # those, the ones the view shows)
    pockets = m.pockets
    assert len(pockets) >= 2
    assert scene.meshes["pockets"].n_cells == int((pockets.cells >= 0).sum())
    assert scene.meshes["mouths"].n_cells == len(pockets.facets)
    for name in ("pockets", "mouths"):
        assert scene.layers[name].actor.GetVisibility() == window.layers_panel.styles[
            name].visible
    cell = int(np.flatnonzero(pockets.cells == 0)[0])
    window.inspector.inspect_vertices(window.model.dataset.ac.simplices(3)[cell])
    assert "pocket 1 of" in window.inspect_panel.fields["pocket"].text()


@pytest.mark.skipif(PDB is None, reason=DATA_ABSENT)
def test_measures_before_the_topology_are_kept(window, qtbot, held_measures, monkeypatch):
    topology = hold(monkeypatch, "with_topology")
    try:
        open_table(qtbot, window, PDB)
        with qtbot.waitSignal(window.model.measuresChanged, timeout=BUILD_TIMEOUT_MS):
            held_measures.set()
        measures = window.model.dataset.molecule
        assert measures is not None and not window.model.dataset.has_topology
        with qtbot.waitSignal(window.model.topologyChanged, timeout=BUILD_TIMEOUT_MS):
            topology.set()
    finally:
        topology.set()
    ds = window.model.dataset
    assert ds.has_topology and ds.molecule is measures
    assert "4,668.88 Å²" in window.info_panel.data.text()
    assert window.scene.meshes["pockets"].n_cells == int((measures.pockets.cells >= 0).sum())


def test_a_file_switched_mid_job_ignores_the_stale_measures(window, qtbot, monkeypatch):
    """The first file's measures finish after the second file is shown: they are dropped,
    the second file's come in (its own atoms), and the dock never showed the first's."""
    release = hold(monkeypatch, "with_measures", cancellable=False)
    adopted = []
    window.model.measuresChanged.connect(lambda: adopted.append(window.model.dataset))
    try:
        first, second = MOLECULES / "gemmi_4hhh_frag.pdb", MOLECULES / "gemmi_HEM.pdb"
        open_table(qtbot, window, first)
        assert window.model.dataset.needs_measures and window.measures.is_busy()
        open_table(qtbot, window, second)
        assert window.model.dataset.path == second and window.model.dataset.molecule is None
        release.set()
        wait_for_measures(qtbot, window)
        qtbot.waitUntil(lambda: not window.measures.is_busy(), timeout=BUILD_TIMEOUT_MS)
    finally:
        release.set()
    measured = {ds.path: result.molecule for ds, result in release.calls}
    assert set(measured) == {first, second}  # the first one's job did finish, ignored
    assert len(adopted) == 1 and adopted[0].path == second
    ds = window.model.dataset
    assert ds.molecule is measured[second] and ds.molecule.atoms == len(ds.ac.input_index)
    assert measured[first].atoms != measured[second].atoms
    assert f"{ds.molecule.surface_area:,.2f} Å²" in window.info_panel.data.text()


def test_closing_while_measuring(window, qtbot, held_measures, monkeypatch):
    """Closing the window while the measures run leaves them behind; their late result
    reaches nothing (no crash, no error)."""
    open_table(qtbot, window, MOLECULES / "gemmi_HEM.pdb")
    assert window.measures.is_busy()
    dataset = window.model.dataset
    monkeypatch.setattr("app.main_window.CLOSE_WAIT_MS", 100)  # the job is held: wait less
    window.close()
    held_measures.set()
    qtbot.waitUntil(lambda: window.measures.wait(0), timeout=BUILD_TIMEOUT_MS)
    qtbot.wait(50)
    assert window.model.dataset is dataset and dataset.molecule is None


def test_failed_measures_are_said_everywhere(window, qtbot, monkeypatch):
    """Measures that fail leave the shape and slider, and say so: the info dock no longer
    says they are being computed, Export pockets says why there are none instead of asking
    to wait, and Inspect's pocket field says they are unknown."""
    import app.menus
    import app.worker
    from app.menus import MenuTools, on_export_pockets
    from core.errors import InputError

    def failing(dataset, check=None):
        raise InputError("the balls' measures went wrong")

    monkeypatch.setattr(app.worker, "with_measures", failing)
    said = []
    monkeypatch.setattr(app.menus.QMessageBox, "information",
                        lambda _parent, _title, text: said.append(text))
    open_table(qtbot, window, MOLECULES / "gemmi_HEM.pdb")
    qtbot.waitUntil(lambda: window.model.measures_failure is not None,
                    timeout=BUILD_TIMEOUT_MS)
    assert "the balls' measures went wrong" in window.status.text()
    wait_for_topology(qtbot, window)  # a later status line (topology, a step) keeps saying it
    window.model.set_index(window.model.index + 1)
    assert "failed: the balls' measures went wrong" in window.status.text()
    text = window.info_panel.data.text()
    assert MEASURING not in text and "measures failed" in text
    tools = MenuTools(window, window.prefs, window.model, window.scene, window.jobs,
                      window.job_progress, window.report, window.open_asking)
    on_export_pockets(tools)
    assert len(said) == 1 and "could not be computed" in said[0]
    assert "try again" not in said[0]
    window.inspector.inspect_vertices(window.model.dataset.ac.simplices(3)[0])
    assert "failed" in window.inspect_panel.fields["pocket"].text()


def test_export_pockets_before_the_measures_asks_to_wait(window, qtbot, held_measures,
                                                         monkeypatch):
    """File → Export pockets while a molecule's pockets are computed asks for no file and
    says they are coming; once they came, it asks where to write them."""
    import app.menus
    from app.menus import MenuTools, on_export_pockets

    said, asked = [], []
    monkeypatch.setattr(app.menus.QMessageBox, "information",
                        lambda _parent, _title, text: said.append(text))
    monkeypatch.setattr(app.menus.file_actions, "ask_save_path",
                        lambda *args: asked.append(args) or None)
    open_table(qtbot, window, MOLECULES / "gemmi_HEM.pdb")
    tools = MenuTools(window, window.prefs, window.model, window.scene, window.jobs,
                      window.job_progress, window.report, window.open_asking)
    on_export_pockets(tools)
    assert len(said) == 1 and "still being computed" in said[0] and not asked
    with qtbot.waitSignal(window.model.measuresChanged, timeout=BUILD_TIMEOUT_MS):
        held_measures.set()
    on_export_pockets(tools)
    assert len(said) == 1 and len(asked) == 1


def test_an_older_molecules_failure_is_not_said_over_a_new_file(window, qtbot, monkeypatch,
                                                                 tmp_path):
    """A molecule's measures that fail after another file (no molecule: nothing supersedes
    them) is shown say nothing: the status line is the new file's."""
    import app.worker
    from core.errors import InputError

    release = threading.Event()

    def failing(dataset, check=None):
        assert release.wait(RELEASE_TIMEOUT_S)
        raise InputError("the balls' measures went wrong")

    monkeypatch.setattr(app.worker, "with_measures", failing)
    cloud = tmp_path / "cloud.csv"
    np.savetxt(cloud, np.random.default_rng(4).normal(size=(300, 3)), delimiter=",",
               header="x,y,z", comments="")
    try:
        open_table(qtbot, window, MOLECULES / "gemmi_HEM.pdb")
        open_table(qtbot, window, cloud)
    finally:
        release.set()
    qtbot.waitUntil(lambda: not window.measures.is_busy(), timeout=BUILD_TIMEOUT_MS)
    qtbot.wait(50)
    assert window.model.dataset.path == cloud and not window.model.dataset.is_molecule
    assert "went wrong" not in window.status.text()
    assert window.model.measures_failure is None
