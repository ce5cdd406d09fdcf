"""An FMU instance through fmpy, FMI 2.0 or 3.0, its log messages kept: the
one place that instantiates and frees one (ContactFMU and PatchFMU open
theirs here)."""
from __future__ import annotations

import ctypes
import weakref
from typing import Callable

from ..runtime import signals_held, unzipped

# on_message(status, category, message): an FMI log call, its texts decoded
OnMessage = Callable[[int, str, str], None]

# fmpy's logger proxy (fmpy.logging.addLoggerProxy: it formats the message in
# C) calls one Python logger for the whole process, the one registered last:
# each FMI 2.0 message goes to its own instance's on_message by the instance
# name it carries (a later instance of the same name takes the name over).
_FMI2_INSTANCES: weakref.WeakValueDictionary = weakref.WeakValueDictionary()
_fmi2_logger = None   # the one ctypes logger, kept for the process's life


def _fmi2_log(env, instance, status, category, message):
    s = _FMI2_INSTANCES.get(instance.decode(errors="replace") if instance else "")
    if s is not None:
        s.orthocontact_on_message(status, category.decode(errors="replace"),
                                  message.decode(errors="replace"))


def instantiate(path, md, instance_name: str, on_message: OnMessage, logging_on: bool = False):
    """(fmpy's FMU2Slave or FMU3Slave, instantiated; the callbacks, which the
    caller keeps alive as long as the instance) of the Co-Simulation FMU at
    `path` whose model description fmpy read as `md`; its log messages go to
    `on_message`, and only its own, however many instances the process holds.
    fmpy changes the
    working folder to the FMU's binaries while it loads them and back after:
    an interrupt in between left the command in that folder, and its
    relative paths (the staging folder of a relative --out) pointing
    elsewhere, so the two happen with the signals held."""
    model = md.coSimulation.modelIdentifier
    if md.fmiVersion.startswith("2"):
        from fmpy.fmi2 import (
            FMU2Slave,
            calloc,
            fmi2CallbackAllocateMemoryTYPE,
            fmi2CallbackFreeMemoryTYPE,
            fmi2CallbackFunctions,
            fmi2CallbackLoggerTYPE,
            free,
        )
        from fmpy.logging import addLoggerProxy

        global _fmi2_logger
        if _fmi2_logger is None:
            _fmi2_logger = fmi2CallbackLoggerTYPE(_fmi2_log)
        cb = fmi2CallbackFunctions()
        cb.logger = _fmi2_logger
        cb.allocateMemory = fmi2CallbackAllocateMemoryTYPE(calloc)
        cb.freeMemory = fmi2CallbackFreeMemoryTYPE(free)
        addLoggerProxy(ctypes.byref(cb))  # formats the printf-style message in C
        folder = unzipped(path)
        with signals_held():   # the working folder changes and comes back in here
            s = FMU2Slave(guid=md.guid, unzipDirectory=folder, modelIdentifier=model,
                          instanceName=instance_name)
        s.orthocontact_on_message = on_message
        _FMI2_INSTANCES[instance_name] = s
        s.instantiate(callbacks=cb, loggingOn=logging_on)
        return s, (cb,)
    from fmpy.fmi3 import FMU3Slave

    def log3(env, status, category, message):
        on_message(status, category.decode(errors="replace"), message.decode(errors="replace"))
    folder = unzipped(path)
    with signals_held():   # as above
        s = FMU3Slave(guid=md.guid, unzipDirectory=folder, modelIdentifier=model,
                      instanceName=instance_name)
    s.instantiate(loggingOn=logging_on, logMessage=log3)
    return s, (log3,)


# FMI 3.0's function of each integer type a model description can give
# (fmpy's ModelVariable.type); FMI 2.0 has one for all, Integer.
_FMI3_INTEGER_FUNCTION = {"Int32": "Int32", "UInt64": "UInt64", "Int64": "Int64", "Enumeration": "Int64"}


def integer_call(slave, fmi_version: int, type_name: str, get: bool = False):
    """The bound fmpy method of `slave` that sets (get=True: gets) a variable
    of integer type `type_name` as its model description declares it:
    setInteger in FMI 2.0; in FMI 3.0 its type's own, setInt32, setUInt64
    (a structural parameter, the dimension of an array: the ContactPatch's
    n1, n2) or setInt64 (an enumeration).  Another type: ValueError."""
    if fmi_version == 2:
        return slave.getInteger if get else slave.setInteger
    if type_name not in _FMI3_INTEGER_FUNCTION:
        raise ValueError(f"no FMI 3.0 integer function for a variable of type {type_name!r}")
    return getattr(slave, ("get" if get else "set") + _FMI3_INTEGER_FUNCTION[type_name])


def free(slave, initialized: bool) -> None:
    """Terminates (if it was initialized) and frees the instance; a failed
    terminate (already terminated, or in error) does not keep it from being freed."""
    if initialized:
        try:
            slave.terminate()
        except Exception:  # fmpy raises a plain Exception on an error status
            pass
    slave.freeInstance()


class FreedOnClose:
    """What an FMU instance's owner does on close(), on leaving a `with`
    block and when collected: frees the fmpy instance in `_slave` (terminated
    first if `initialized`), once."""
    _slave = None
    initialized = False

    def close(self):
        # forgotten before it is freed: an interrupt between the two must not
        # free it twice (here and again when collected: a crash)
        slave, self._slave = self._slave, None
        if slave is not None:
            free(slave, self.initialized)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def __del__(self):
        try:
            self.close()
        except Exception:   # at interpreter exit fmpy may be half torn down
            pass
