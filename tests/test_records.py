"""artiplan.records.dataclass builds the classes dataclasses.dataclass builds.

Every class is made twice from one body, once by each decorator; the two must agree on what
their instances do: equality, hashes, reprs, signatures, errors, fields, replace, pickling.
"""

from __future__ import annotations

import copy
import dataclasses
import functools
import inspect
import math
import pickle
from collections.abc import Callable
from typing import Any

import pytest

from artiplan import records

DECORATORS = {"stdlib": dataclasses.dataclass, "records": records.dataclass}
FIELDS = {dataclasses.dataclass: dataclasses.field, records.dataclass: records.field}
OPTIONS = [{}, {"frozen": True}, {"frozen": True, "slots": True}, {"slots": True},
           {"eq": False}, {"repr": False}, {"frozen": True, "eq": False},
           {"init": False}]


def shapes(dc: Callable[..., Any], opts: dict[str, Any]) -> dict[str, type]:
    """Classes of several shapes, each made by ``dc(**opts)``."""
    field = FIELDS[dc]

    @dc(**opts)
    class Empty:
        """No fields."""

    @dc(**opts)
    class One:
        """One field."""

        value: float

    @dc(**opts)
    class Node:
        name: str
        args: tuple[str, ...] = ()
        loc: object = field(default=None, compare=False, repr=False)
        tags: list[str] = field(default_factory=list)
        weight: float = field(default=1.0, hash=False)

    @dc(**opts)
    class SelfField:
        """A field named ``self``."""

        self: int
        other: int = 2

    return {"Empty": Empty, "One": One, "Node": Node, "SelfField": SelfField}


ARGS: dict[str, tuple[tuple[Any, ...], ...]] = {
    "Empty": ((),),
    "One": ((1.5,), (2.0,), (math.nan,)),
    "Node": (("a",), ("a", ("x", "y")), ("a", (), "loc1", ["t"], 2.0), ("b", (), None, [], 1.0)),
    "SelfField": ((1,), (1, 3)),
}


def _both(opts: dict[str, Any]) -> list[tuple[type, type, tuple[Any, ...]]]:
    std, own = shapes(DECORATORS["stdlib"], opts), shapes(DECORATORS["records"], opts)
    return [(std[k], own[k], a) for k in std for a in ARGS[k]]


def _outcome(fn: Callable[[], Any]) -> tuple[str, Any]:
    try:
        return "ok", fn()
    except Exception as exc:  # the type and message must agree too
        return type(exc).__name__, str(exc)


@pytest.fixture(params=[100, 0], ids=["generic-init", "compiled-init"])
def compile_after(request, monkeypatch) -> int:  # type: ignore[no-untyped-def]
    """Instances made by the generic __init__ first, or by the compiled one at once."""
    monkeypatch.setattr(records._LazyInit, "COMPILE_AFTER", request.param)
    return int(request.param)


@pytest.mark.parametrize("opts", OPTIONS, ids=lambda o: ",".join(o) or "default")
def test_same_instances(opts: dict[str, Any], compile_after: int) -> None:
    seen: set[type] = set()
    for std, own, args in _both(opts):
        if opts.get("init") is False:
            continue
        if own not in seen:
            seen.add(own)
            assert records.is_generic_init(vars(own)["__init__"])  # no compile yet
        s1, s2, o1, o2 = std(*args), std(*args), own(*args), own(*args)
        names = records.names(std)
        kw = dict(zip(names, args, strict=False))
        assert dataclasses.astuple(own(**kw)) == dataclasses.astuple(std(**kw))
        assert (o1 == o2) == (s1 == s2)
        assert (o1 != o2) == (s1 != s2)
        assert (o1 == s1) is False  # other classes never compare equal
        if opts.get("repr", True):
            assert repr(o1).replace(own.__qualname__, "C") \
                == repr(s1).replace(std.__qualname__, "C")
        else:
            assert own.__repr__ is std.__repr__ is object.__repr__
        hashes = _outcome(lambda o1=o1: hash(o1)), _outcome(lambda s1=s1: hash(s1))
        if opts.get("eq", True):
            assert hashes[0] == hashes[1]  # the same value, or the same error
        else:
            assert hashes[0][0] == hashes[1][0] == "ok"  # identity hashes
        assert dataclasses.asdict(o1) == dataclasses.asdict(s1)
        assert dataclasses.astuple(o1) == dataclasses.astuple(s1)
        for name in [*names, "extra"]:
            writes = (_outcome(lambda o1=o1, n=name: setattr(o1, n, 9)),
                      _outcome(lambda s1=s1, n=name: setattr(s1, n, 9)))
            deletes = (_outcome(lambda o1=o1, n=name: delattr(o1, n)),
                       _outcome(lambda s1=s1, n=name: delattr(s1, n)))
            if opts.get("slots") and opts.get("frozen") and name == "extra":
                # Python 3.11's frozen slots classes check against the class from before the
                # slots were added: a TypeError from super() instead of FrozenInstanceError.
                assert writes[0][0] == deletes[0][0] == "FrozenInstanceError"
                continue
            assert writes[0] == writes[1] and deletes[0] == deletes[1]
        for replace in (dataclasses.replace, records.replace):
            r1, r2 = replace(own(*args)), replace(std(*args))
            assert type(r1) is own and type(r2) is std
            assert dataclasses.astuple(r1) == dataclasses.astuple(r2)
            if names:
                assert getattr(replace(own(*args), **{names[0]: 5}), names[0]) == 5
                assert _outcome(functools.partial(replace, own(*args), nope=1))[0] \
                    == _outcome(functools.partial(replace, std(*args), nope=1))[0] == "TypeError"
        c1, c2 = copy.deepcopy(own(*args)), copy.deepcopy(std(*args))
        assert (c1 == own(*args)) == (c2 == std(*args))


def test_init_compiled_when_it_pays_off() -> None:
    @records.dataclass(frozen=True)
    class Pair:
        a: int
        b: list[int] = records.field(default_factory=list)

    limit = records._LazyInit.COMPILE_AFTER
    made = [Pair(k) for k in range(limit - 1)] + [Pair(a=1, b=[2])]
    assert records.is_generic_init(vars(Pair)["__init__"])  # generic so far
    assert made[3] == Pair(3) and made[-1].b == [2] and made[0].b is not made[1].b
    Pair(5)
    assert not records.is_generic_init(vars(Pair)["__init__"])  # compiled now
    assert Pair(5) == made[5]

    @records.dataclass
    class Single:
        a: int

    with pytest.raises(TypeError, match="unexpected keyword argument 'c'"):
        Single(1, c=2)  # a call that does not bind: the compiled __init__'s own error
    assert not records.is_generic_init(vars(Single)["__init__"])


@pytest.mark.parametrize("opts", OPTIONS, ids=lambda o: ",".join(o) or "default")
def test_same_classes(opts: dict[str, Any]) -> None:
    for std, own, _ in _both(opts):
        assert own.__doc__ == std.__doc__
        assert str(inspect.signature(own)) == str(inspect.signature(std))
        assert not records.is_generic_init(vars(own).get("__init__"))  # read: compiled
        assert own.__init__.__qualname__.split(".")[-1] == std.__init__.__qualname__.split(".")[-1]
        assert own.__match_args__ == std.__match_args__  # type: ignore[attr-defined]
        assert getattr(own, "__slots__", None) == getattr(std, "__slots__", None)
        assert (own.__hash__ is None) == (std.__hash__ is None)
        assert repr(own.__dataclass_params__) == repr(std.__dataclass_params__)  # type: ignore[attr-defined]
        assert [(f.name, f.type, f.default, f.default_factory, f.repr, f.compare, f.hash,
                 f.metadata, f.kw_only, f.init) for f in dataclasses.fields(own)] \
            == [(f.name, f.type, f.default, f.default_factory, f.repr, f.compare, f.hash,
                 f.metadata, f.kw_only, f.init) for f in dataclasses.fields(std)]
        assert dataclasses.is_dataclass(own) and records.names(own) == records.names(std)
        assert {k: repr(v) for k, v in vars(own).items() if not k.startswith("__")} \
            == {k: repr(v) for k, v in vars(std).items() if not k.startswith("__")}  # defaults


@pytest.mark.parametrize("opts", OPTIONS[:4], ids=lambda o: ",".join(o) or "default")
def test_same_errors(opts: dict[str, Any], compile_after: int) -> None:
    std, own = shapes(DECORATORS["stdlib"], opts), shapes(DECORATORS["records"], opts)
    for bad_args, bad_kw in (((), {}), (("a", (), None, [], 1.0, "extra"), {}),
                             (("a",), {"name": "b"}), (("a",), {"nope": 1})):
        o = _outcome(functools.partial(own["Node"], *bad_args, **bad_kw))
        s = _outcome(functools.partial(std["Node"], *bad_args, **bad_kw))
        assert o[0] == s[0] == "TypeError"
        assert o[1].replace(own["Node"].__qualname__, "C") \
            == s[1].replace(std["Node"].__qualname__, "C")


def test_factories_nan_post_init_and_recursion(compile_after: int) -> None:
    for dc in DECORATORS.values():

        @dc
        class Bag:
            items: list[Any] = FIELDS[dc](default_factory=list)
            seen: int = 0

            def __post_init__(self) -> None:
                self.seen += 1

        a, b = Bag(), Bag()
        assert a.items is not b.items and a.seen == 1
        a.items.append(a)
        assert repr(a).endswith("Bag(items=[...], seen=1)")
        assert Bag.__hash__ is None

        @dc(frozen=True)
        class Num:
            x: float

        nan = math.nan
        assert Num(nan) == Num(nan)  # the same object: tuple comparison's identity rule
        assert Num(float("nan")) != Num(float("nan"))


def test_standard_fields_and_lazy_metadata() -> None:
    @records.dataclass(frozen=True)
    class Mixed:
        a: int
        b: list[int] = dataclasses.field(default_factory=list)  # the stdlib's field() works too
        c: int = records.field(default=3, metadata={"unit": "s"})

    assert "__dataclass_fields__" in vars(Mixed)  # a stand-in until first read
    assert not isinstance(vars(Mixed)["__dataclass_fields__"], dict)
    m = Mixed(1)
    assert m.b == [] and m.c == 3 and Mixed.c == 3 and "b" not in vars(Mixed)
    assert [f.name for f in dataclasses.fields(m)] == ["a", "b", "c"]
    assert isinstance(vars(Mixed)["__dataclass_fields__"], dict)  # made by dataclasses now
    assert dataclasses.fields(Mixed)[2].metadata["unit"] == "s"
    assert dataclasses.asdict(m) == {"a": 1, "b": [], "c": 3}
    assert records.names(Mixed) == ("a", "b", "c") == records.names(m)


def test_explicit_methods_are_kept() -> None:
    for dc in DECORATORS.values():

        @dc(frozen=True)
        class Custom:
            x: int

            def __repr__(self) -> str:
                return "custom"

            def __eq__(self, other: object) -> bool:
                return True

        assert repr(Custom(1)) == "custom" and Custom(1) == Custom(2)
        assert hash(Custom(1)) == hash((1,))  # the implicit None is replaced, as documented

        @dc(frozen=True)
        class Hashed:
            x: int

            def __hash__(self) -> int:
                return 7

        assert hash(Hashed(1)) == 7

        @dc
        class Mutable:
            x: int

            def __eq__(self, other: object) -> bool:
                return True

        assert Mutable.__hash__ is None
        with pytest.raises(TypeError, match="Cannot overwrite attribute __setattr__"):

            @dc(frozen=True)
            class Bad:
                x: int

                def __setattr__(self, name: str, value: Any) -> None:
                    pass


def test_subclasses() -> None:
    @records.dataclass(frozen=True)
    class Base:
        x: int

    class Plain(Base):
        pass

    p = Plain(1)
    with pytest.raises(dataclasses.FrozenInstanceError):
        p.x = 2  # type: ignore[misc]
    p.y = 3  # type: ignore[attr-defined]  # not a field: allowed, as with the stdlib

    @dataclasses.dataclass(frozen=True)
    class Child(Base):
        y: int = 0

    assert Child(1, 2) == Child(1, 2) and Child(1).x == 1
    assert records.names(Child) == ("x", "y") and records.names(Plain) == ("x",)
    assert records.replace(Child(1, 2), y=3) == Child(1, 3)
    assert records.replace(p, x=5).x == 5 and type(records.replace(p)) is Plain
    with pytest.raises(TypeError, match="dataclass base"):
        records.dataclass(frozen=True)(type("Sub", (Base,), {"__annotations__": {"z": "int"}}))


def test_unsupported_options_refused() -> None:
    for opts in ({"order": True}, {"unsafe_hash": True}, {"kw_only": True}, {"nope": 1}):
        with pytest.raises(TypeError, match="does not support"):
            records.dataclass(**opts)
    with pytest.raises(TypeError, match="init=False"):

        @records.dataclass
        class Hidden:
            x: int = records.field(default=0, init=False)


@records.dataclass(frozen=True, slots=True)
class PickledSlots:
    a: int
    b: tuple[int, ...] = ()


@records.dataclass(frozen=True)
class PickledDict:
    a: int
    b: tuple[int, ...] = ()


@pytest.mark.parametrize("cls", [PickledSlots, PickledDict])
def test_pickle(cls: type) -> None:
    obj = cls(1, (2, 3))
    back = pickle.loads(pickle.dumps(obj))
    assert back == obj and hash(back) == hash(obj) and back is not obj
