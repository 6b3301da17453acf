"""The messages between the window and its processes cross the boundary as plain data and
come back as the same frozen dataclasses (app.messages)."""

from __future__ import annotations

import json

import pytest

from app import messages
from app.messages import (
    BuildJob,
    Failed,
    Finished,
    OpeningFound,
    Reported,
    TableHandedOver,
    TableRead,
    TopologyJob,
    TopologyWritten,
    from_plain,
    to_plain,
)
from core.modes.alpha_modes import Mode, make_mode

EXAMPLES = [
    Reported(0.25, "building"),
    Finished(OpeningFound(0.5)),
    Finished("plain text"),
    Failed("InputError", "too few points"),
    BuildJob(Mode(), False, "/cache/entry.npz", None, "/dev/shm/alphascoop-shared-1-x"),
    BuildJob(make_mode(8, "max", 0.7, True), True, None, "gmsh", None),
    TableHandedOver("/dev/shm/x", True, "/dev/shm/x/cursor", "/tmp/b/saving.lock"),
    TableHandedOver("/cache/entry.npz", False, None, "/tmp/b/saving.lock"),
    OpeningFound(None),
    TopologyJob("/cache/entry.npz", "/cache/entry.npz", "/tmp/t/topology.npz", None),
    TableRead(),
    TopologyWritten("/tmp/t/topology.npz"),
]


@pytest.mark.parametrize("message", EXAMPLES, ids=lambda m: type(m).__name__)
def test_a_message_crosses_as_plain_data_and_comes_back_equal(message):
    plain = to_plain(message)
    assert json.loads(json.dumps(plain)) == plain  # nothing but plain data
    back = from_plain(plain)
    assert type(back) is type(message) and back == message


def test_every_message_class_is_frozen_and_has_an_example():
    for cls in messages.MESSAGES.values():
        assert cls.__dataclass_params__.frozen
    assert {type(m) for m in EXAMPLES} == set(messages.MESSAGES.values())


@pytest.mark.parametrize("plain", [{"kind": "Nothing"}, {"kind": "Reported", "fraction": 1.0},
                                   {"kind": "TableRead", "extra": 1}, {"fraction": 1.0}])
def test_unknown_or_incomplete_messages_are_refused(plain):
    with pytest.raises(ValueError, match="not a message"):
        from_plain(plain)


def test_plain_values_pass_as_they_are():
    assert to_plain("x") == from_plain("x") == "x"
    assert to_plain(None) is from_plain(None) is None
