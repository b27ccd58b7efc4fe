"""The shared depth guard (:mod:`mawdo.util.nesting`): its count agrees with the depth of the parsed
data, text nested past the limit is refused before the parser sees it, in time linear in its
length, and the scenario reader's own guard counts the same (so it can use this one)."""

from __future__ import annotations

import json
import time
import tomllib

import pytest
from hypothesis import given
from hypothesis import strategies as st

from mawdo.util.nesting import MAX_NESTING, NestingError, loads, nesting_depth


def _depth(value) -> int:
    # the reference: nesting of the parsed data (lists and dicts), counted recursively
    if isinstance(value, list):
        return 1 + max((_depth(v) for v in value), default=0)
    if isinstance(value, dict):
        return 1 + max((_depth(v) for v in value.values()), default=0)
    return 0


JSON_DATA = st.recursive(
    st.none() | st.booleans() | st.integers() | st.text(alphabet="[]{}\"'\\#ab \n"),
    lambda inner: (
        st.lists(inner, max_size=3) | st.dictionaries(st.text(max_size=3), inner, max_size=3)
    ),  # fmt: skip
    max_leaves=20,
)


@given(JSON_DATA)
def test_the_json_count_is_the_depth_of_the_parsed_data(data):
    text = json.dumps(data)
    assert nesting_depth(text, toml=False)[0] == _depth(json.loads(text))


@pytest.mark.parametrize("depth", [1, 4, 9, 31])
def test_the_toml_count_skips_strings_and_comments(depth):
    inner: object = 7
    for _ in range(depth - 1):
        inner = [inner]
    toml = ('t = "[[[[ \\" [[["\nu = \'[[[[\'\nv = """[[[\n[[["""\n# [[[[[[[\nw = '
            + json.dumps(inner) + "\n")  # fmt: skip
    # (a TOML document's root table has no brackets in the text)
    assert nesting_depth(toml, toml=True)[0] == _depth(tomllib.loads(toml)) - 1


def test_the_line_of_the_first_too_deep_bracket_is_named():
    text = 'a = 1\nb = "[[["\nc = ' + "[" * 40 + "]" * 40 + "\n"
    with pytest.raises(NestingError, match=r"plan\.toml: .* more than 32 deep \(line 3\); x"):
        loads(text, "toml", what="plan.toml", needs="x")
    assert loads(text, "toml", limit=40)["c"] is not None  # within a higher limit: parsed


@pytest.mark.parametrize("fmt", ["toml", "json"])
def test_deep_text_is_refused_fast_and_shallow_text_parses(fmt):
    deep = "[" * 100_000 + "]" * 100_000
    text = f"x = {deep}\n" if fmt == "toml" else f'{{"x": {deep}}}'
    t0 = time.monotonic()
    with pytest.raises(NestingError, match=f"more than {MAX_NESTING} deep"):
        loads(text, fmt)
    assert time.monotonic() - t0 < 10  # the scan is linear; tomllib took 65 s to fail
    ok = "x = [[1], {a = [2]}]\n" if fmt == "toml" else '{"x": [[1], {"a": [2]}]}'
    assert loads(ok, fmt) == {"x": [[1], {"a": [2]}]}


def test_syntax_errors_are_left_to_the_caller():
    with pytest.raises(json.JSONDecodeError):
        loads("[1,", "json")
    with pytest.raises(tomllib.TOMLDecodeError):
        loads("x = [1,", "toml")
