"""ROS 1 message classes, made from the field definitions of rosbags' ROS 1 Noetic typestore.

The classes a node under the stand-in imports (``from geometry_msgs.msg import Twist``) are
not written out by hand: each is generated, on first use, from the definition of the same
type in ``rosbags`` (``get_typestore(Stores.ROS1_NOETIC)``), the library the project already
writes its bags with (:mod:`ifgm_ref.io.bags`). They behave as ``genpy``'s classes do in ROS 1:
every field has a default (numbers 0, strings empty, nested messages default-constructed,
``time`` and ``duration`` zero, arrays of fixed length filled, sequences empty), fields are
mutable, and a class takes its fields by position or by keyword. Constants are class
attributes. ``std_srvs``' three services, which the typestore (a store of *messages*) does
not hold, are read with rosbags' own parser from their definitions.

Between processes a message travels as JSON (:func:`to_wire`, :func:`from_wire`): a list of
its fields in order, ``time`` and ``duration`` as ``[secs, nsecs]``.

>>> Twist = message_class("geometry_msgs/Twist")
>>> cmd = Twist()
>>> cmd.linear.x = 0.3
>>> cmd
geometry_msgs/Twist(linear=geometry_msgs/Vector3(x=0.3, y=0.0, z=0.0), angular=geometry_msgs/Vector3(x=0.0, y=0.0, z=0.0))
>>> from_wire("geometry_msgs/Twist", to_wire(cmd)) == cmd
True
"""  # noqa: E501

from __future__ import annotations

import functools
from collections.abc import Mapping
from typing import Any, ClassVar, cast

from rosbags.interfaces import Nodetype
from rosbags.typesys import Stores, get_types_from_msg, get_typestore

from ifgm_ref.io.ros.rostime import Duration, Time

__all__ = [
    "SERVICES",
    "Message",
    "ServiceType",
    "from_wire",
    "message_class",
    "package_namespace",
    "service_class",
    "to_wire",
]

#: The services a node may offer and call between its processes (their ROS 1 definitions:
#: request, response).
SERVICES: Mapping[str, tuple[str, str]] = {
    "std_srvs/SetBool": ("bool data", "bool success\nstring message"),
    "std_srvs/Empty": ("", ""),
    "std_srvs/Trigger": ("", "bool success\nstring message"),
}
#: rosbags' names of the built-in ``time`` and ``duration``, and their classes here.
SPANS: Mapping[str, type[Time] | type[Duration]] = {
    "builtin_interfaces/msg/Time": Time,
    "builtin_interfaces/msg/Duration": Duration,
}
_INTS = frozenset({"int8", "uint8", "int16", "uint16", "int32", "uint32", "int64", "uint64"})
_FLOATS = frozenset({"float32", "float64"})

#: A field's type as rosbags describes it: ``(Nodetype, detail)``.
Spec = tuple[Nodetype, Any]


#: The typestores: ROS 1 Noetic for rospy nodes, ROS 2 Humble for rclpy nodes.
STORES = {"ros1": Stores.ROS1_NOETIC, "ros2": Stores.ROS2_HUMBLE}


@functools.cache
def _definitions(distro: str = "ros1") -> dict[str, tuple[list[Any], list[tuple[str, Spec]]]]:
    """rosbags' field definitions by its names (``pkg/msg/Name``), std_srvs' added."""
    found = dict(get_typestore(STORES[distro]).fielddefs)
    for name, texts in SERVICES.items():
        package, base = name.split("/")
        for part, text in zip(("Request", "Response"), texts, strict=True):
            found.update(get_types_from_msg(text, f"{package}/msg/{base}{part}"))
    return cast(dict[str, tuple[list[Any], list[tuple[str, Spec]]]], found)


def _key(ros1_type: str, distro: str = "ros1") -> str:
    """rosbags' name of a type: ``geometry_msgs/Twist`` -> ``geometry_msgs/msg/Twist``."""
    parts = ros1_type.split("/")
    if len(parts) == 2:
        parts.insert(1, "msg")
    key = "/".join(parts)
    if len(parts) != 3 or key not in _definitions(distro):
        raise ValueError(f"unknown message type {ros1_type!r}")
    return key


class Message:
    """The base of every generated message class (``genpy.Message``'s interface)."""

    __slots__ = ()
    #: The ROS 1 type name, ``package/Name``.
    _type: ClassVar[str] = ""
    #: The fields' names and rosbags types, in order.
    _spec: ClassVar[tuple[tuple[str, Spec], ...]] = ()
    #: ``ros1`` or ``ros2``: which typestore made it.
    _distro: ClassVar[str] = "ros1"

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        names = [name for name, _ in self._spec]
        if len(args) > len(names):
            raise TypeError(f"{self._type} takes at most {len(names)} fields, got {len(args)}")
        values = dict(zip(names, args, strict=False))
        for name, value in kwargs.items():
            if name not in names or name in values:
                raise TypeError(f"{self._type}: unknown or repeated field {name!r}")
            values[name] = value
        for name, spec in self._spec:
            setattr(self, name, values[name] if name in values else _default(spec, self._distro))

    def __eq__(self, other: object) -> bool:
        if type(other) is not type(self):
            return NotImplemented
        return all(getattr(self, n) == getattr(other, n) for n, _ in self._spec)

    __hash__ = None  # type: ignore[assignment]  # mutable, as genpy's

    def __repr__(self) -> str:
        inner = ", ".join(f"{n}={getattr(self, n)!r}" for n, _ in self._spec)
        return f"{self._type}({inner})"


def _default(spec: Spec, distro: str = "ros1") -> Any:
    """A field's default value (genpy's; ROS 2's time is a message)."""
    kind, detail = spec
    if kind is Nodetype.BASE:
        name = detail[0]
        return (
            "" if name == "string" else False if name == "bool" else 0.0 if name in _FLOATS else 0
        )
    if kind is Nodetype.NAME:
        if detail in SPANS and distro == "ros1":
            return SPANS[detail]()
        return _class_of_key(detail, distro)()
    inner, length = detail
    return [_default(inner, distro) for _ in range(length)] if kind is Nodetype.ARRAY else []


@functools.cache
def _class_of_key(key: str, distro: str = "ros1") -> type[Message]:
    """The class of rosbags type ``key``, generated once."""
    consts, fields = _definitions(distro)[key]
    package, _, base = key.split("/")
    namespace: dict[str, Any] = {
        "__slots__": tuple(name for name, _ in fields),
        "_type": f"{package}/{base}",
        "_spec": tuple(fields),
        "_distro": distro,
        "__module__": f"{package}.msg",
    }
    namespace.update({name: value for name, _, value in consts})
    return type(base, (Message,), namespace)


def message_class(ros1_type: str, distro: str = "ros1") -> type[Any]:
    """The class of the ROS 1 message type ``ros1_type`` (``sensor_msgs/LaserScan``).

    >>> message_class("std_msgs/String")().data
    ''
    >>> message_class("nav_msgs/Odometry")().pose.covariance == [0.0] * 36
    True

    Raises
    ------
    ValueError
        For a type the typestore does not hold.
    """
    return _class_of_key(_key(ros1_type, distro), distro)


class ServiceType:
    """A service type (``std_srvs/SetBool``): its request and response classes (also as
    ``Request`` and ``Response``, ROS 2's names)."""

    _type: ClassVar[str] = ""
    _request_class: ClassVar[type[Message]]
    _response_class: ClassVar[type[Message]]
    Request: ClassVar[type[Message]]
    Response: ClassVar[type[Message]]


@functools.cache
def service_class(ros1_type: str, distro: str = "ros1") -> type[ServiceType]:
    """The service type ``ros1_type``, one of :data:`SERVICES`.

    >>> SetBool = service_class("std_srvs/SetBool")
    >>> SetBool._request_class(True).data, SetBool._response_class().message
    (True, '')
    """
    if ros1_type not in SERVICES:
        raise ValueError(f"unknown service type {ros1_type!r}; known: {', '.join(SERVICES)}")
    package, base = ros1_type.split("/")
    request = message_class(f"{package}/{base}Request", distro)
    response = message_class(f"{package}/{base}Response", distro)
    namespace: dict[str, Any] = {"_type": ros1_type, "Request": request, "Response": response}
    namespace.update({"_request_class": request, "_response_class": response})
    return type(base, (ServiceType,), {**namespace, "__module__": f"{package}.srv"})


def package_namespace(package: str, kind: str, distro: str = "ros1") -> dict[str, Any]:
    """What ``package.msg`` or ``package.srv`` (``kind``) exports: every class by name.

    >>> sorted(package_namespace("std_srvs", "srv"))[:3]
    ['Empty', 'EmptyRequest', 'EmptyResponse']
    """
    if kind == "srv":
        found: dict[str, Any] = {}
        for name in SERVICES:
            if name.startswith(package + "/"):
                service = service_class(name, distro)
                base = name.split("/")[1]
                found[base] = service
                found[base + "Request"] = service._request_class
                found[base + "Response"] = service._response_class
        return found
    prefix = f"{package}/msg/"
    keys = [k for k in _definitions(distro) if k.startswith(prefix)]
    if package == "std_srvs":
        keys = []
    return {key[len(prefix) :]: _class_of_key(key, distro) for key in keys}


def to_wire(message: Message) -> list[Any]:
    """``message`` as JSON-ready data: its fields in order, converted by their types."""
    return [_value_to_wire(getattr(message, n), spec) for n, spec in message._spec]


def _value_to_wire(value: Any, spec: Spec) -> Any:
    kind, detail = spec
    if kind is Nodetype.BASE:
        name = detail[0]
        if name in _FLOATS:
            return float(value)
        if name in _INTS:
            return int(value)
        return bool(value) if name == "bool" else str(value)
    if kind is Nodetype.NAME:
        if isinstance(value, Time | Duration):
            return [value.secs, value.nsecs]
        if not isinstance(value, Message):
            raise TypeError(f"expected a message of type {detail}, got {value!r}")
        return to_wire(value)
    inner = detail[0]
    return [_value_to_wire(item, inner) for item in value]


def from_wire(ros1_type: str, data: list[Any], distro: str = "ros1") -> Message:
    """The message of type ``ros1_type`` that :func:`to_wire` gave as ``data``.

    Raises
    ------
    ValueError
        For an unknown type, or data that does not fit it.
    """
    return _from_wire_key(_key(ros1_type, distro), data, distro)


def _from_wire_key(key: str, data: list[Any], distro: str) -> Message:
    cls = _class_of_key(key, distro)
    if not isinstance(data, list) or len(data) != len(cls._spec):
        raise ValueError(f"{cls._type}: expected {len(cls._spec)} fields, got {data!r:.80}")
    message = cls.__new__(cls)
    for (name, spec), item in zip(cls._spec, data, strict=True):
        setattr(message, name, _value_from_wire(item, spec, distro))
    return message


def _value_from_wire(item: Any, spec: Spec, distro: str) -> Any:
    kind, detail = spec
    if kind is Nodetype.BASE:
        return item
    if kind is Nodetype.NAME:
        if detail in SPANS and distro == "ros1":
            return SPANS[detail](int(item[0]), int(item[1]))
        return _from_wire_key(detail, item, distro)
    inner = detail[0]
    if inner[0] is Nodetype.BASE:
        return list(item)
    return [_value_from_wire(x, inner, distro) for x in item]
