"""The explorer's state (Qt-evented, no widgets, no VTK): the dataset and the alpha index.

Signals fire only on real change; the alpha is an index into the dataset's spectrum, so every
value is a critical alpha and every critical alpha is reachable.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
from PySide6.QtCore import QObject, Signal

from app.dataset import Dataset
from app.history import AlphaHistory
from app.log_travel import snap_index
from core.complex import at_value
from core.molecule.cavities import cavity_cells

__all__ = ["ExplorerModel", "snap_index"]


class ExplorerModel(QObject):
    """Current dataset and alpha index; the shape at that alpha is queried lazily and cached."""

    datasetChanged = Signal()
    alphaChanged = Signal()
    topologyChanged = Signal()  # the dataset's topology (signatures, optimal alpha) arrived
    measuresChanged = Signal()  # a molecule's measures (area, cavities, pockets) arrived
    datasetReleased = Signal()  # the dataset was let go (a new load starts): no dataset now

    def __init__(self) -> None:
        """Start empty: no dataset, index -1."""
        super().__init__()
        self.dataset: Dataset | None = None
        self.index = -1
        self._shape = None
        self._cursor = None
        self.history = AlphaHistory()
        self.touched = False  # the alpha moved since the dataset opened (user or --alpha)
        self.measures_failure: str | None = None  # why a molecule's measures failed (None: not)

    @property
    def spectrum(self) -> np.ndarray:
        """(s,) float64 critical alphas of the dataset (empty without one)."""
        return self.dataset.spectrum if self.dataset else np.zeros(0)

    @property
    def alpha(self) -> float:
        """The current alpha radius (nan without a dataset; for weighted points the signed
        radius sign(alpha2) * sqrt(|alpha2|), negative below zero radius)."""
        return float(self.spectrum[self.index]) if self.dataset else float("nan")

    @property
    def alpha2(self) -> float:
        """The current alpha squared, signed: negative values exist for weighted points."""
        alpha = self.alpha
        return alpha * abs(alpha)

    @property
    def weighted(self) -> bool:
        """True when the dataset's points carry weights (squared radii)."""
        return self.dataset is not None and self.dataset.ac.weights is not None

    @property
    def shape(self):
        """AlphaShape at the current alpha (queried once per index, by the dataset's cursor:
        a step costs what changed since the last shape)."""
        if self._shape is None and self.dataset is not None:
            self._shape = self._cursor.move(**at_value(self.alpha))
        return self._shape

    def cavities(self) -> np.ndarray:
        """(k, 4) int32 cells of the voids at the current alpha (a molecule's cavities)."""
        ac = self.dataset.ac
        return ac.simplices(3)[cavity_cells(ac, self.alpha2)]

    def set_dataset(self, dataset: Dataset) -> None:
        """Replace the dataset and move to its opening (default) alpha."""
        self.dataset = dataset
        self.measures_failure = None
        self._cursor = dataset.cursor or dataset.ac.cursor()
        self.index = self.default_index()
        self.history.reset(self.index)
        self.touched = False
        self._shape = None
        self.datasetChanged.emit()
        self.alphaChanged.emit()

    def release(self) -> None:
        """Let the dataset go (before a new one loads, so two are never in memory at once);
        emits datasetReleased when there was one."""
        if self.dataset is None:
            return
        self.dataset, self._cursor, self._shape = None, None, None
        self.index = -1
        self.history.reset(self.index)
        self.touched = False
        self.datasetReleased.emit()

    def set_topology(self, dataset: Dataset) -> bool:
        """Take the topology-complete version of the current dataset (same table: the same
        TableIndex), keeping a molecule's measures that arrived before it; unless the alpha
        moved since the dataset opened, go to its opening alpha. False (nothing done) for
        another dataset's result."""
        if not self._same_table(dataset):
            return False
        if dataset.needs_measures and self.dataset.molecule is not None:  # came meanwhile
            dataset = replace(dataset, molecule=self.dataset.molecule)
        self.dataset = dataset
        self.topologyChanged.emit()
        if not self.touched:
            self.set_index(self.default_index(), record=False)
            self.history.reset(self.index)
            self.touched = False
        return True

    def set_measures(self, dataset: Dataset) -> bool:
        """Take a molecule's measures from `dataset`, a measured version of the current one
        (same table); the topology it may lack is kept. False (nothing done) for another
        dataset's result."""
        if not self._same_table(dataset) or dataset.molecule is None:
            return False
        self.dataset = replace(self.dataset, molecule=dataset.molecule)
        self.measuresChanged.emit()
        return True

    def fail_measures(self, message: str) -> bool:
        """The current molecule's measures failed (`message` says why): they will not come;
        emits measuresChanged so what waited for them says so. False (nothing done) when
        the current dataset awaits none (the failure was an older dataset's)."""
        if self.dataset is None or not self.dataset.needs_measures:
            return False
        self.measures_failure = message
        self.measuresChanged.emit()
        return True

    def _same_table(self, dataset: Dataset) -> bool:
        """dataset is a version of the current one: the same table (the same TableIndex)."""
        return self.dataset is not None and dataset.ac.index is self.dataset.ac.index

    def set_index(self, index: int, record: bool = True) -> None:
        """Move to spectrum[index] (clamped); emits alphaChanged only when it changes.

        The move is recorded in `history` (Back/Forward) unless `record` is False.
        """
        if self.dataset is None:
            return
        index = int(np.clip(index, 0, len(self.spectrum) - 1))
        if index == self.index:
            return
        if record:
            self.history.visit(index)
        self.index = index
        self.touched = True
        self._shape = None
        self.alphaChanged.emit()

    def go_back(self) -> None:
        """Return to the alpha visited before (undo for the slider)."""
        index = self.history.back() if self.dataset is not None else None
        if index is not None:
            self.set_index(index, record=False)

    def go_forward(self) -> None:
        """Redo a go_back."""
        index = self.history.forward() if self.dataset is not None else None
        if index is not None:
            self.set_index(index, record=False)

    def set_alpha(self, alpha: float) -> None:
        """Move to the shape at alpha (snapped to the critical value at or below it)."""
        if self.dataset is not None:
            self.set_index(snap_index(self.spectrum, alpha))

    def set_alpha2(self, alpha2: float) -> None:
        """Move to the shape at a squared alpha (any sign), snapped like set_alpha."""
        self.set_alpha(float(np.copysign(np.sqrt(abs(alpha2)), alpha2)))

    def default_index(self) -> int:
        """Index of the dataset's opening alpha (where a new dataset starts)."""
        return snap_index(self.spectrum, self.dataset.default_alpha) if self.dataset else -1

    def optimal_index(self) -> int:
        """Index of the dataset's optimal alpha (the current index until the topology that
        gives it is known; -1 without a dataset)."""
        if self.dataset is None:
            return -1
        if self.dataset.optimal_alpha is None:
            return self.index
        return snap_index(self.spectrum, self.dataset.optimal_alpha)

    def hull_index(self) -> int:
        """Index of the last critical alpha: the whole triangulation (convex hull)."""
        return len(self.spectrum) - 1
