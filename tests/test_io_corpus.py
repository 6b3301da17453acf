"""Real files from other projects' test data (tests/data/corpus, origins in SOURCES.md): point
count, bounding box and attributes must match MANIFEST.json, which independent readers wrote
(tests/data/corpus/make_manifest.py: plyfile, laspy, pye57, pygltflib, numpy parsers)."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from core.io import read_points

CORPUS = Path(__file__).resolve().parent / "data" / "corpus"
MANIFEST = json.loads((CORPUS / "MANIFEST.json").read_text())


@pytest.mark.parametrize("name", sorted(MANIFEST))
def test_corpus_file_matches_independent_reader(name):
    expected = MANIFEST[name]
    report = read_points(CORPUS / name).report
    assert report.n_read == expected["points"]
    np.testing.assert_allclose(report.bbox, expected["bbox"], rtol=1e-12, atol=1e-12)
    assert sorted(report.attributes) == expected["attributes"]


def test_every_corpus_file_is_in_the_manifest_and_sources():
    sources = (CORPUS / "SOURCES.md").read_text()
    files = {str(p.relative_to(CORPUS)) for p in CORPUS.rglob("*")
             if p.is_file() and p.suffix not in (".md", ".json", ".py", ".bin")}
    assert files == set(MANIFEST)
    assert all(f"`{name}`" in sources for name in files)


def test_corpus_stays_small():
    total = sum(p.stat().st_size for p in CORPUS.rglob("*") if p.is_file())
    assert total < 2_000_000
    assert len({Path(n).parts[0] for n in MANIFEST}) >= 8  # formats
