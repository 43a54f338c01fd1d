"""``dataclass``: the standard library's decorator, without its cost at start-up.

On Python < 3.13 ``dataclasses.dataclass`` writes the source of ``__init__``, ``__repr__``,
``__eq__``, ``__hash__``, ``__setattr__`` and ``__delattr__`` and compiles each (~0.6 ms a frozen
class), and importing ``dataclasses`` imports ``inspect`` (~8 ms). With the ~100 classes on the
path of ``artiplan plan`` that was more than half of its start-up. This module makes the same
classes without either:

* ``__init__`` is a closure for a class's first instances and the standard library's text,
  compiled once that pays off (:class:`_LazyInit`); ``__repr__``, ``__eq__``, ``__hash__`` and
  the frozen ``__setattr__``/``__delattr__`` are closures with the same results, hashes, reprs
  and errors; ``__match_args__``, ``__slots__``, ``__doc__`` and class attributes are the same;
* ``__dataclass_fields__`` and ``__dataclass_params__`` appear when first read, made by
  ``dataclasses`` itself, so ``dataclasses.fields``, ``replace``, ``asdict`` and ``is_dataclass``
  work as ever; :func:`replace` and :func:`names` here do not need them.

tests/test_records.py checks each class shape against the standard library's. What differs:
``pprint`` prints these instances on one line (it recognises the standard library's generated
``__repr__`` only). mypy sees ``dataclasses.dataclass``, ``field`` and ``replace`` themselves.

Supported: ``init``, ``repr``, ``eq``, ``frozen``, ``match_args``, ``slots``; fields with
``default``, ``default_factory``, ``repr``, ``hash``, ``compare``, ``metadata``; ``__post_init__``.
Anything else (``order``, ``unsafe_hash``, ``kw_only``, ``init=False`` fields, ``ClassVar`` or
``InitVar`` pseudo-fields, a dataclass among the bases) is refused with a ``TypeError``: use
``dataclasses.dataclass`` for such a class.
"""

from __future__ import annotations

import _thread
import abc
import sys
from operator import attrgetter

TYPE_CHECKING = False  # mypy reads any ``TYPE_CHECKING`` as true; no typing import at run time
if TYPE_CHECKING:
    from collections.abc import Callable
    from typing import Any, TypeVar

    T = TypeVar("T")

__all__ = ["dataclass", "field", "names", "replace"]


class _Sentinel:
    """A marker: no default (``MISSING``), or a parameter's default that calls the field's
    ``default_factory`` (``<factory>``, as the standard library shows it)."""

    def __init__(self, text: str) -> None:
        self.text = text

    def __repr__(self) -> str:
        return self.text


MISSING: Any = _Sentinel("MISSING")
_FACTORY = _Sentinel("<factory>")
_UNSUPPORTED = ("order", "unsafe_hash", "kw_only", "weakref_slot")


class Field:
    """What ``field()`` says about one field (``dataclasses.Field``'s attributes)."""

    __slots__ = ("name", "type", "default", "default_factory", "init", "repr", "hash",
                 "compare", "metadata", "kw_only")

    def __init__(self, *, default: Any = MISSING, default_factory: Any = MISSING,
                 init: bool = True, repr: bool = True, hash: bool | None = None,
                 compare: bool = True, metadata: Any = None, kw_only: Any = MISSING) -> None:
        if default is not MISSING and default_factory is not MISSING:
            raise ValueError("cannot specify both default and default_factory")
        self.name: str = ""
        self.type: Any = None
        self.default, self.default_factory, self.init, self.repr = (default, default_factory,
                                                                     init, repr)
        self.hash, self.compare, self.metadata, self.kw_only = hash, compare, metadata, kw_only


def _dataclass(cls: type[T] | None = None, /, *, init: bool = True, repr: bool = True,
               eq: bool = True, frozen: bool = False, match_args: bool = True,
               slots: bool = False, **unsupported: Any) -> Any:
    """``dataclasses.dataclass`` for the options in the module docstring."""
    if unsupported and (any(unsupported.get(k) for k in _UNSUPPORTED)
                        or set(unsupported) - set(_UNSUPPORTED)):
        raise TypeError(f"artiplan.records.dataclass does not support {sorted(unsupported)}: "
                        "use dataclasses.dataclass")

    def wrap(c: type[T]) -> type[T]:
        return _process(c, {"init": init, "repr": repr, "eq": eq, "frozen": frozen,
                            "match_args": match_args}, slots)

    return wrap if cls is None else wrap(cls)


def _process(cls: type[T], params: dict[str, bool], slots: bool) -> type[T]:
    if any("__dataclass_fields__" in vars(b) for b in cls.__mro__[1:]):
        raise TypeError(f"{cls.__name__}: a dataclass base is not supported here: use "
                        "dataclasses.dataclass")
    fields = _collect(cls)
    own = dict(cls.__dict__)
    class_hash = own.get("__hash__", MISSING)
    explicit_hash = not (class_hash is MISSING or (class_hash is None and "__eq__" in own))
    if slots:
        cls = _with_slots(cls, fields)
    cls.__record_fields__ = fields  # type: ignore[attr-defined]
    for attr in ("__dataclass_fields__", "__dataclass_params__"):
        setattr(cls, attr, _Standard(cls, params, attr))
    names = tuple(f.name for f in fields)
    if params["init"]:
        _check_defaults(fields)
        if "__init__" not in own:
            _LazyInit(cls, fields, params["frozen"])  # puts the class's __init__
    if params["repr"] and "__repr__" not in own:
        _attach(cls, _repr_fn(tuple(f.name for f in fields if f.repr)))
    if params["eq"] and "__eq__" not in own:
        _attach(cls, _eq_fn(_key(tuple(f.name for f in fields if f.compare))))
    if params["frozen"]:
        for fn in _frozen_fns(cls, names):
            if fn.__name__ in own:
                raise TypeError(f"Cannot overwrite attribute {fn.__name__} in class "
                                f"{cls.__name__}")
            _attach(cls, fn)
        if slots:
            for name, method in (("__getstate__", _getstate), ("__setstate__", _setstate)):
                if name not in own:
                    setattr(cls, name, method)
    if params["eq"] and not explicit_hash:
        if params["frozen"]:
            hashed = tuple(f.name for f in fields if (f.compare if f.hash is None else f.hash))
            _attach(cls, _hash_fn(_key(hashed)))
        else:
            cls.__hash__ = None  # type: ignore[assignment]
    if not cls.__doc__:
        cls.__doc__ = cls.__name__ + _signature_text(cls, fields, params["init"])
    if params["match_args"] and "__match_args__" not in own:
        setattr(cls, "__match_args__", names)  # noqa: B010 (mypy: a read-only name)
    abc.update_abstractmethods(cls)
    return cls


def _collect(cls: type) -> tuple[Field, ...]:
    """The fields of ``cls`` (its annotations), class attributes set as ``dataclasses`` does."""
    annotations = cls.__dict__.get("__annotations__", {})
    std = sys.modules.get("dataclasses")  # its field() is accepted too, if it was imported
    fields = []
    for name, tp in annotations.items():
        text = tp if isinstance(tp, str) else repr(tp)
        if ("Var" in text or "KW_ONLY" in text) and (
                text.lstrip().split("[", 1)[0].rsplit(".", 1)[-1].strip()
                in ("ClassVar", "InitVar", "KW_ONLY") or "dataclasses.KW_ONLY" in text):
            raise TypeError(f"{cls.__name__}.{name}: ClassVar/InitVar/KW_ONLY are not "
                            "supported here: use dataclasses.dataclass")
        default = getattr(cls, name, MISSING)
        spec = _as_field(default, std)
        if spec is None:
            f = _plain_field(default)
        else:
            f = spec
            if f.kw_only is True or not f.init:
                raise TypeError(f"{cls.__name__}.{name}: kw_only and init=False fields are "
                                "not supported here: use dataclasses.dataclass")
        if f.default is not MISSING and f.default.__class__.__hash__ is None:
            raise ValueError(f"mutable default {type(f.default)} for field {name} is not "
                             "allowed: use default_factory")
        f.name, f.type = name, tp
        if spec is not None:
            if f.default is MISSING:
                delattr(cls, name)
            else:
                setattr(cls, name, f.default)
        fields.append(f)
    for name, value in cls.__dict__.items():
        if name not in annotations and _as_field(value, std) is not None:
            raise TypeError(f"{name!r} is a field but has no type annotation")
    return tuple(fields)


def _plain_field(default: Any) -> Field:
    """``Field(default=default)``, made without its keyword checks (most fields are these)."""
    f = Field.__new__(Field)
    f.default, f.default_factory, f.init, f.repr, f.hash, f.compare, f.metadata, f.kw_only = (
        default, MISSING, True, True, None, True, None, MISSING)
    return f


def _as_field(value: Any, std: Any) -> Field | None:
    """``value`` as a field's description if it is one (``field()`` of this module or of
    ``dataclasses``, the module ``std`` when imported), else None."""
    if value.__class__ is Field:
        return value
    if std is None or not isinstance(value, std.Field):
        return None
    return Field(**{k: MISSING if v is std.MISSING else v for k, v in (
        (k, getattr(value, k)) for k in Field.__slots__[2:])})


def _with_slots(cls: type, fields: tuple[Field, ...]) -> type:
    """``cls`` made again with ``__slots__`` (as ``dataclasses`` does)."""
    if "__slots__" in cls.__dict__:
        raise TypeError(f"{cls.__name__} already specifies __slots__")
    inherited: set[str] = set()
    for base in cls.__mro__[1:-1]:
        slots = base.__dict__.get("__slots__", ())
        inherited.update((slots,) if isinstance(slots, str) else slots)
    body = dict(cls.__dict__)
    body["__slots__"] = tuple(f.name for f in fields if f.name not in inherited)
    for f in fields:
        body.pop(f.name, None)
    body.pop("__dict__", None)
    body.pop("__weakref__", None)
    qualname = cls.__qualname__
    new = type(cls)(cls.__name__, cls.__bases__, body)
    new.__qualname__ = qualname
    return new


class _Standard:
    """``__dataclass_fields__`` or ``__dataclass_params__`` until first read: then made by
    ``dataclasses`` itself (on a twin class with the same fields and options) and put on the
    class in place of both."""

    __slots__ = ("cls", "params", "attr")

    def __init__(self, cls: type, params: dict[str, bool], attr: str) -> None:
        self.cls, self.params, self.attr = cls, params, attr

    def __get__(self, obj: Any, owner: type | None = None) -> Any:
        import dataclasses

        cls: Any = self.cls
        annotations: dict[str, Any] = {}
        body: dict[str, Any] = {"__module__": cls.__module__, "__qualname__": cls.__qualname__,
                                "__annotations__": annotations}
        for f in cls.__record_fields__:
            annotations[f.name] = f.type
            body[f.name] = dataclasses.field(
                default=dataclasses.MISSING if f.default is MISSING else f.default,
                default_factory=(dataclasses.MISSING if f.default_factory is MISSING
                                 else f.default_factory),
                repr=f.repr, hash=f.hash, compare=f.compare, metadata=f.metadata)
        twin: Any = dataclasses.dataclass(type(cls.__name__, (), body), **self.params)
        type.__setattr__(cls, "__dataclass_fields__", twin.__dataclass_fields__)
        type.__setattr__(cls, "__dataclass_params__", twin.__dataclass_params__)
        return getattr(cls, self.attr)


def _attach(cls: type, fn: Callable[..., Any]) -> None:
    fn.__qualname__ = f"{cls.__qualname__}.{fn.__name__}"
    setattr(cls, fn.__name__, fn)


def _check_defaults(fields: tuple[Field, ...]) -> None:
    seen_default = False
    for f in fields:
        if f.default is not MISSING or f.default_factory is not MISSING:
            seen_default = True
        elif seen_default:
            raise TypeError(f"non-default argument {f.name!r} follows default argument")


class _LazyInit:
    """A class's ``__init__`` until its compiled one pays off. The first ``COMPILE_AFTER``
    instances are made by a generic ``__init__`` (a closure, made at the first instance: no
    compile); then, or when ``inspect.signature`` reads it, or at a call that does not bind
    (for the exact error), the standard library's text is compiled (~0.1 ms) and put in its
    place. Most classes of a short run never need it. The generic one is a plain function in
    the class (a descriptor would cost each instance a Python-level ``__get__``); its
    ``__wrapped__`` is this object, whose ``__signature__`` is the compiled one's."""

    __slots__ = ("cls", "fields", "frozen", "calls")

    COMPILE_AFTER = 100

    def __init__(self, cls: type, fields: tuple[Field, ...], frozen: bool) -> None:
        self.cls, self.fields, self.frozen, self.calls = cls, fields, frozen, 0
        lazy = self

        def __init__(obj: Any, /, *args: Any, **kwargs: Any) -> None:
            # the first instance: the generic __init__ takes this one's place
            if _LazyInit.COMPILE_AFTER <= 0:
                lazy.compiled()(obj, *args, **kwargs)
                return
            generic = _generic_init(lazy.cls, lazy.fields, lazy.frozen, lazy)
            if lazy.cls.__dict__.get("__init__") is __init__:
                lazy._put(generic)
            generic(obj, *args, **kwargs)

        self._put(__init__)

    def _put(self, fn: Callable[..., None]) -> None:
        fn.__wrapped__ = self  # type: ignore[attr-defined]
        _attach(self.cls, fn)

    def compiled(self) -> Callable[..., None]:
        """The compiled ``__init__``, now in the class."""
        fn = self.cls.__dict__["__init__"]
        if getattr(fn, "__wrapped__", None) is self:
            fn = _init_fn(self.cls, self.fields, self.frozen)
            _attach(self.cls, fn)
        return fn

    @property
    def __signature__(self) -> Any:
        import inspect  # only when something inspects the class

        return inspect.signature(self.compiled())

    def __call__(self, *args: Any, **kwargs: Any) -> None:
        self.compiled()(*args, **kwargs)


def is_generic_init(fn: Any) -> bool:
    """True while ``fn`` (a class's ``__init__``) is not the compiled one yet."""
    return isinstance(getattr(fn, "__wrapped__", None), _LazyInit)


def _generic_init(cls: type, fields: tuple[Field, ...], frozen: bool,
                  lazy: _LazyInit) -> Callable[..., None]:
    """An ``__init__`` for every call that binds (the others go to ``lazy.compiled()``), up to
    ``COMPILE_AFTER`` calls."""
    compiled = lazy.compiled
    names = tuple(f.name for f in fields)
    index = {name: i for i, name in enumerate(names)}
    n, required = len(names), sum(f.default is MISSING and f.default_factory is MISSING
                                  for f in fields)
    defaults = tuple(f.default if f.default_factory is MISSING else f.default_factory
                     for f in fields)
    factory = tuple(f.default_factory is not MISSING for f in fields)
    put = object.__setattr__ if frozen else setattr
    post_init = hasattr(cls, "__post_init__")
    # the fields land in the instance's __dict__ whichever way they are set: one update then
    # does what a put per field does (the compiled __init__ keeps the standard library's text)
    direct = _plain_fields(cls, names) and (frozen or cls.__setattr__ is object.__setattr__)

    def __init__(self: Any, /, *args: Any, **kwargs: Any) -> None:
        lazy.calls += 1
        if lazy.calls > _LazyInit.COMPILE_AFTER:
            compiled()(self, *args, **kwargs)
            return
        given = len(args)
        if kwargs or given != n:
            if given > n or any(index.get(k, -1) < given for k in kwargs) \
                    or any(names[i] not in kwargs for i in range(given, required)):
                compiled()(self, *args, **kwargs)  # raises the standard library's error
                return
            for i, name in enumerate(names):
                if i < given:
                    value = args[i]
                elif name in kwargs:
                    value = kwargs[name]
                else:
                    value = defaults[i]() if factory[i] else defaults[i]
                put(self, name, value)
        elif direct and self.__class__ is cls:
            self.__dict__.update(zip(names, args, strict=True))
        else:
            for name, value in zip(names, args, strict=True):
                put(self, name, value)
        if post_init:
            self.__post_init__()

    return __init__


def _plain_fields(cls: type, names: tuple[str, ...]) -> bool:
    """True if instances of ``cls`` keep every field in their ``__dict__``: they have one, and
    no class on the MRO makes a field name a data descriptor (a slot, a property)."""
    if not cls.__dictoffset__:
        return False
    for name in names:
        for klass in cls.__mro__:
            if name in vars(klass):
                kind = type(vars(klass)[name])
                if hasattr(kind, "__set__") or hasattr(kind, "__delete__"):
                    return False
                break
    return True


def _init_fn(cls: type, fields: tuple[Field, ...], frozen: bool) -> Callable[..., None]:
    self_name = "__dataclass_self__" if any(f.name == "self" for f in fields) else "self"
    ns: dict[str, Any] = {"__name__": cls.__module__, "_FACTORY": _FACTORY,
                          "__dataclass_builtins_object__": object}
    params, body, direct = [self_name], [], []
    for f in fields:
        value = f.name
        if f.default_factory is not MISSING:
            ns[f"_dflt_{f.name}"] = f.default_factory
            params.append(f"{f.name}=_FACTORY")
            value = f"_dflt_{f.name}() if {f.name} is _FACTORY else {f.name}"
        elif f.default is not MISSING:
            ns[f"_dflt_{f.name}"] = f.default
            params.append(f"{f.name}=_dflt_{f.name}")
        else:
            params.append(f.name)
        body.append(f"__dataclass_builtins_object__.__setattr__({self_name},{f.name!r},{value})"
                    if frozen else f"{self_name}.{f.name}={value}")
        direct.append(f"__dataclass_dict__[{f.name!r}]={value}")
    if frozen and fields and _plain_fields(cls, tuple(f.name for f in fields)):
        # the fields land in the instance's __dict__ (see _plain_fields): writing it is what
        # object.__setattr__ does there, at about half the cost; a subclass gets the original
        ns["__dataclass_cls__"] = cls
        body = [f"if {self_name}.__class__ is __dataclass_cls__:",
                f"  __dataclass_dict__ = {self_name}.__dict__",
                *(f"  {line}" for line in direct), "else:", *(f"  {line}" for line in body)]
    if hasattr(cls, "__post_init__"):
        body.append(f"{self_name}.__post_init__()")
    lines = "\n".join(f"  {b}" for b in body or ["pass"])
    exec(f"def __init__({','.join(params)}):\n{lines}", ns)
    fn: Callable[..., None] = ns["__init__"]
    fn.__annotations__ = {**{f.name: f.type for f in fields}, "return": None}
    return fn


def _signature_text(cls: type, fields: tuple[Field, ...], init: bool) -> str:
    """``str(inspect.signature(cls))`` without ``-> None``, as ``dataclasses`` puts in the
    ``__doc__`` of a class without one (written here when every annotation is a string)."""
    if init and is_generic_init(cls.__dict__.get("__init__")) \
            and all(isinstance(f.type, str) for f in fields):
        parts = []
        for f in fields:
            default = ("<factory>" if f.default_factory is not MISSING
                       else "" if f.default is MISSING else repr(f.default))
            parts.append(f"{f.name}: {f.type!r}" + (f" = {default}" if default else ""))
        return "(" + ", ".join(parts) + ")"
    import inspect

    try:
        return str(inspect.signature(cls)).replace(" -> None", "")
    except (TypeError, ValueError):
        return ""


def _key(names: tuple[str, ...]) -> Callable[[Any], tuple[Any, ...]]:
    """The tuple of the named attributes of an object (as ``(self.a, self.b,)``)."""
    if len(names) > 1:
        return attrgetter(*names)
    if not names:
        return lambda obj: ()
    get = attrgetter(names[0])
    return lambda obj: (get(obj),)


def _eq_fn(key: Callable[[Any], tuple[Any, ...]]) -> Callable[[Any, Any], Any]:
    def __eq__(self: Any, other: Any) -> Any:
        if other.__class__ is self.__class__:
            return key(self) == key(other)
        return NotImplemented

    return __eq__


def _hash_fn(key: Callable[[Any], tuple[Any, ...]]) -> Callable[[Any], int]:
    def __hash__(self: Any) -> int:
        return hash(key(self))

    return __hash__


def _repr_fn(names: tuple[str, ...]) -> Callable[[Any], str]:
    running: set[tuple[int, int]] = set()

    def __repr__(self: Any) -> str:
        guard = id(self), _thread.get_ident()
        if guard in running:
            return "..."
        running.add(guard)
        try:
            return (self.__class__.__qualname__ + "("
                    + ", ".join([f"{n}={getattr(self, n)!r}" for n in names]) + ")")
        finally:
            running.discard(guard)

    return __repr__


def _frozen_fns(cls: type, names: tuple[str, ...]) -> tuple[Callable[..., None], ...]:
    def __setattr__(self: Any, name: str, value: Any) -> None:
        if type(self) is cls or name in names:
            from dataclasses import FrozenInstanceError

            raise FrozenInstanceError(f"cannot assign to field {name!r}")
        super(cls, self).__setattr__(name, value)  # type: ignore[arg-type]

    def __delattr__(self: Any, name: str) -> None:
        if type(self) is cls or name in names:
            from dataclasses import FrozenInstanceError

            raise FrozenInstanceError(f"cannot delete field {name!r}")
        super(cls, self).__delattr__(name)  # type: ignore[arg-type]

    return __setattr__, __delattr__


def _getstate(self: Any) -> list[Any]:
    return [getattr(self, f.name) for f in _own_fields(type(self)) or ()]


def _setstate(self: Any, state: list[Any]) -> None:
    for f, value in zip(_own_fields(type(self)) or (), state, strict=False):
        object.__setattr__(self, f.name, value)


def _own_fields(cls: type) -> tuple[Field, ...] | None:
    """The fields of the nearest dataclass among ``cls`` and its bases if this module made
    it, else None (a class of ``dataclasses``, or none)."""
    for k in cls.__mro__:
        found = vars(k).get("__record_fields__")
        if found is not None or "__dataclass_fields__" in vars(k):
            return found
    return None


def names(cls_or_obj: Any) -> tuple[str, ...]:
    """The field names of a dataclass (made here or by ``dataclasses``) or of an instance."""
    found = _own_fields(cls_or_obj if isinstance(cls_or_obj, type) else type(cls_or_obj))
    if found is None:
        import dataclasses

        return tuple(f.name for f in dataclasses.fields(cls_or_obj))
    return tuple(f.name for f in found)


def _replace(obj: T, /, **changes: Any) -> T:
    """``dataclasses.replace``."""
    found = None if isinstance(obj, type) else _own_fields(type(obj))
    if found is None:
        import dataclasses

        return dataclasses.replace(obj, **changes)  # type: ignore[type-var]
    for f in found:
        if f.name not in changes:
            changes[f.name] = getattr(obj, f.name)
    return obj.__class__(**changes)


if TYPE_CHECKING:
    from dataclasses import dataclass as dataclass
    from dataclasses import field as field
    from dataclasses import replace as replace
else:
    dataclass, field, replace = _dataclass, Field, _replace
