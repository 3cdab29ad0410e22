"""rospy's services over the broker: ``Service``, ``ServiceProxy``, ``wait_for_service``.

A call is routed by the broker to the node that offers the service and answered at the same
simulated time: the caller waits (its callbacks run meanwhile), the server's handler runs
when the broker hands it control. The service types are ``std_srvs``' ``SetBool``, ``Empty``
and ``Trigger`` (:data:`ifgm_ref.io.ros.messages.SERVICES`).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from ifgm_ref.io.ros.client import Registration, client
from ifgm_ref.io.ros.messages import Message, ServiceType, from_wire, to_wire
from ifgm_ref.io.ros.rospy_api import ROSException, _interruptible
from ifgm_ref.io.ros.rostime import nanoseconds

__all__ = ["Service", "ServiceException", "ServiceProxy", "wait_for_service"]


class ServiceException(ROSException):
    """A call that failed: no such service, or its handler raised."""


class Service:
    """Offer ``name`` of type ``service_class``, answered by ``handler(request)``."""

    def __init__(
        self,
        name: str,
        service_class: type[ServiceType],
        handler: Callable[[Message], Any],
        **_ignored: Any,
    ) -> None:
        self.service_class = service_class
        registration = Registration("srv", name, service_class._type, handler=handler)
        self._registration = client().register(registration)
        self.resolved_name = registration.resolved or name

    def shutdown(self, reason: str = "") -> None:
        """Stop offering the service (the broker answers callers with an error)."""
        self._registration.active = False

    def spin(self) -> None:
        """Wait, serving, until the node shuts down (as ``rospy.spin``)."""
        from ifgm_ref.io.ros.rospy_api import spin

        spin()


class ServiceProxy:
    """Call ``name`` of type ``service_class``: ``proxy(request)``, ``proxy(field, ...)``."""

    def __init__(self, name: str, service_class: type[ServiceType], **_ignored: Any) -> None:
        self.name = name
        self.service_class = service_class

    def __call__(self, *args: Any, **kwargs: Any) -> Any:
        return self.call(*args, **kwargs)

    def call(self, *args: Any, **kwargs: Any) -> Any:
        """Call the service and return its response.

        Raises
        ------
        ServiceException
            When no node offers it or its handler raised.
        """
        request_class = self.service_class._request_class
        if len(args) == 1 and not kwargs and isinstance(args[0], request_class):
            request = args[0]
        else:
            request = request_class(*args, **kwargs)
        node = client()
        ident = node.new_id()
        node.send(
            {
                "op": "call",
                "name": node.resolve(self.name),
                "type": self.service_class._type,
                "id": ident,
                "data": to_wire(request),
            }
        )
        _interruptible(lambda: node.wait(condition=lambda: ident in node.responses))
        reply = node.responses.pop(ident)
        if "error" in reply:
            raise ServiceException(f"service call {self.name} failed: {reply['error']}")
        return from_wire(self.service_class._response_class._type, reply["data"])

    def wait_for_service(self, timeout: float | None = None) -> None:
        """Wait until the service is offered."""
        wait_for_service(self.name, timeout)

    def close(self) -> None:
        """Nothing to close here."""


def wait_for_service(service: str, timeout: float | None = None) -> None:
    """Wait until some node offers ``service``.

    Raises
    ------
    ROSException
        When ``timeout`` s of simulated time pass first.
    """
    node = client()
    name = node.resolve(service)
    if name in node.services_ready:
        return
    node.send({"op": "wait_service", "name": name})
    until = None if timeout is None else node.now + nanoseconds(timeout)
    ready = _interruptible(
        lambda: node.wait(until=until, condition=lambda: name in node.services_ready)
    )
    if not ready:
        raise ROSException(f"timeout exceeded while waiting for service {name}")
