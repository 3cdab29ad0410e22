"""A planner decision of the C port on a Cortex-M4F: code size, stack, and cycles by emulation.

Used by ``benchmarks/bench_c.py`` (``--help`` there); needs ``arm-none-eabi-gcc`` with
newlib (Debian: ``gcc-arm-none-eabi libnewlib-arm-none-eabi``) and the Python packages
``unicorn`` and ``capstone`` (``pip install unicorn capstone``); :func:`missing` names what
is absent.

The build
---------
The port's library is compiled for the Cortex-M4F -- ``-mcpu=cortex-m4 -mthumb
-mfpu=fpv4-sp-d16 -mfloat-abi=hard``, single precision (``-DIFGM_FLOAT``: an M4F's FPU has no
double precision, which newlib would emulate in software), with ``-ffunction-sections`` --
and each planner is linked alone with newlib's libm and ``--gc-sections``, keeping only its
``NAME_init`` and ``NAME_step`` and what they call: the image's ``.text`` is the flash the
planner takes, libm's functions included. newlib's ``<tgmath.h>`` names complex functions
that its ``<complex.h>`` declares only on Cygwin (``ccosl``, ``cacosl`` ...): the build
includes ``examples/c/cortex-m4/newlib_tgmath.h`` first, which declares them (nothing calls
them: every argument is real).

The cycles
----------
The image runs in Unicorn (QEMU's CPU emulator; Cortex-M4 model, FPU on). Each decision is
a call of ``NAME_step`` on the observation the host build parsed (``ifgm_bench --dump``), in
the same order as on the host, every episode from ``NAME_init``. A counted decision's
cycles are the sum, over the instructions it executes, of their cost in the Cortex-M4
Technical Reference Manual (ARM DDI 0439B, table 3-1; FPU: table 7-1), for zero-wait-state
memory:

* 1 cycle for data processing, multiplies, moves, compares, ``VADD``, ``VSUB``, ``VMUL``,
  ``VCMP``, ``VCVT`` and moves between core and FPU registers (2 for a pair);
* 2 for a load or a store (1 right after another one: they pipeline), 3 for ``LDRD``/``STRD``,
  ``1 + N`` for a load or store of ``N`` registers (``PUSH``, ``POP``, ``VPUSH``, ``LDM`` ...);
* 3 for ``VMLA``/``VMLS``/``VFMA`` and their negations, 14 for ``VDIV`` and ``VSQRT``, 2-12 for
  ``SDIV``/``UDIV`` (7 in the nominal estimate);
* a taken branch (``B``, ``BL``, ``BX``, ``CBZ``, a ``POP`` or ``LDR`` of the PC, ``TBB``)
  adds the pipeline refill ``P``: 1 to 3 cycles, 2 in the nominal estimate.

The range reported is ``P = 1`` with the fastest divides to ``P = 3`` with the slowest.
Not modelled: flash wait states (an STM32L4 at 80 MHz has 4, mostly hidden by its ART
accelerator's prefetch and cache), interrupts, and the M4's folding of ``IT`` instructions
(counted as 1 cycle each). The stack is measured too: the deepest the decision writes into
a painted stack, libm's frames included.
"""

from __future__ import annotations

import functools
import importlib
import importlib.util
import shutil
import struct
import subprocess
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import Any, NamedTuple

#: The Cortex-M4F target: Thumb-2, single-precision FPU, floats passed in FPU registers.
ARM_FLAGS = ("-mcpu=cortex-m4", "-mthumb", "-mfpu=fpv4-sp-d16", "-mfloat-abi=hard")
#: Where the emulated program's data lives (an M4's SRAM region starts here).
RAM = 0x2000_0000
#: Stack given to every call, bytes: far more than a decision uses, painted to measure it.
STACK = 64 * 1024
#: The byte the stack is painted with.
PAINT = 0xA5
#: Memory given to the planner's struct, bytes: more than any planner of a float build takes
#: (IFGM's, some 0.8 MB, most of it the remembered points).
PLANNER_RAM = 4 * 1024 * 1024
#: A page with no code: a called function returns here and the emulation stops.
RETURN = 0x7000
#: Pipeline refill of a taken branch, cycles: nominal, least, most (TRM table 3-1: 1 to 3).
REFILL = (2, 1, 3)
#: SDIV/UDIV cycles: nominal, least, most (2 to 12 by the operands' sizes).
DIVIDE = (7, 2, 12)


def missing(cc: str = "arm-none-eabi-gcc") -> list[str]:
    """What the estimate needs and this machine lacks (an empty list if nothing)."""
    absent = [cc] if shutil.which(cc) is None else []
    return absent + [m for m in ("unicorn", "capstone") if importlib.util.find_spec(m) is None]


class Cost(NamedTuple):
    """Cycles of an instruction or a run of them: nominal, least and most."""

    nominal: int
    low: int
    high: int


def instruction_cost(mnemonic: str, operands: int, after_load: bool) -> Cost:
    """Cycles of one instruction, its refill not included (module docstring).

    ``mnemonic`` is capstone's (``ldr.w``, ``vdiv.f32``, ``popeq``); ``operands`` the number
    of 32-bit registers among the operands (a ``d`` register counts 2); ``after_load``
    whether the instruction before was a single core load or store.

    >>> instruction_cost("vdiv.f32", 3, False), instruction_cost("push", 4, False)
    (Cost(nominal=14, low=14, high=14), Cost(nominal=5, low=5, high=5))
    >>> instruction_cost("ldr.w", 2, True), instruction_cost("sdiv", 3, False)
    (Cost(nominal=1, low=1, high=1), Cost(nominal=7, low=2, high=12))
    """
    base = mnemonic.split(".")[0]
    fixed = _FIXED.get(base) or _FIXED.get(base[:-2])  # a condition suffix: addeq -> add
    if fixed is not None:
        return Cost(fixed, fixed, fixed)
    if base.startswith(("sdiv", "udiv")):
        return Cost(*DIVIDE)
    if base.startswith(_MULTIPLE):
        n = 1 + operands - (0 if base.startswith(("push", "pop", "vpush", "vpop")) else 1)
        return Cost(n, n, n)
    if base.startswith(("ldrd", "strd")):
        return Cost(3, 3, 3)
    if base.startswith(("ldr", "str")):
        n = 1 if after_load else 2
        return Cost(n, n, n)
    if base.startswith(("vldr", "vstr")):
        return Cost(2, 2, 2)
    if base.startswith("vmov") and operands >= 3:
        return Cost(2, 2, 2)
    return Cost(1, 1, 1)


#: Instructions of a fixed cost other than 1 (by mnemonic, condition suffix removed).
_FIXED = {
    "vdiv": 14, "vsqrt": 14,
    "vmla": 3, "vmls": 3, "vnmla": 3, "vnmls": 3, "vfma": 3, "vfms": 3, "vfnma": 3, "vfnms": 3,
    "mla": 2, "mls": 2, "tbb": 2, "tbh": 2,
}  # fmt: skip
#: Loads and stores of several registers: 1 + N cycles.
_MULTIPLE = ("ldm", "stm", "push", "pop", "vldm", "vstm", "vpush", "vpop")


@dataclass(frozen=True)
class Block:
    """A straight run of instructions as the emulator executes it: its cost, and whether
    it ends with a branch (the refill is added when the next block is not the next in
    memory)."""

    cost: Cost
    branches: bool


def decode_block(code: bytes, address: int) -> Block:
    """The cost of the Thumb-2 instructions ``code`` at ``address``."""
    capstone = _module("capstone")
    md = _disassembler()
    nominal = low = high = 0
    after_load = branches = False
    for insn in md.disasm(code, address):
        words = sum(
            2 if insn.reg_name(op.reg).startswith("d") else 1
            for op in insn.operands
            if op.type == capstone.arm.ARM_OP_REG
        )
        cost = instruction_cost(insn.mnemonic, words, after_load)
        nominal, low, high = nominal + cost.nominal, low + cost.low, high + cost.high
        base = insn.mnemonic.split(".")[0]
        after_load = base.startswith(("ldr", "str")) and not base.startswith(("ldrd", "strd"))
        writes_pc = any(
            op.type == capstone.arm.ARM_OP_REG and op.reg == capstone.arm.ARM_REG_PC
            for op in insn.operands
        )
        branches = writes_pc or any(
            insn.group(g) for g in (capstone.CS_GRP_JUMP, capstone.CS_GRP_CALL, capstone.CS_GRP_RET)
        )
    return Block(Cost(nominal, low, high), branches)


def _module(name: str) -> Any:
    """An optional dependency (untyped: its attributes are ``Any``)."""
    return importlib.import_module(name)


@functools.cache
def _disassembler() -> Any:
    capstone = _module("capstone")
    md = capstone.Cs(capstone.CS_ARCH_ARM, capstone.CS_MODE_THUMB | capstone.CS_MODE_MCLASS)
    md.detail = True
    return md


# ---- the build ---------------------------------------------------------------------------


def link_planner(name: str, library: Path, out: Path, cc: str = "arm-none-eabi-gcc") -> Path:
    """Link planner ``name``'s ``NAME_init`` and ``NAME_step`` from ``library`` (the port's
    library built for the M4F) with newlib's libm into ``out``, keeping nothing else."""
    subprocess.run(
        [cc, *ARM_FLAGS, "--specs=nosys.specs", "-nostartfiles", "-Wl,--gc-sections",
         f"-Wl,--entry={name}_step", f"-Wl,--undefined={name}_init", str(library), "-lm",
         "-o", str(out)],
        check=True,
    )  # fmt: skip
    return out


class Image(NamedTuple):
    """An ELF image: its loadable segments ``(address, bytes, memory size)`` and symbols."""

    segments: tuple[tuple[int, bytes, int], ...]
    symbols: dict[str, int]


def read_elf(path: Path) -> Image:
    """The segments and the function and object symbols of a 32-bit little-endian ELF."""
    data = path.read_bytes()
    (phoff, shoff) = struct.unpack_from("<II", data, 0x1C)
    phentsize, phnum, shentsize, shnum = struct.unpack_from("<HHHH", data, 0x2A)
    segments = []
    for i in range(phnum):
        kind, offset, vaddr, _, filesz, memsz = struct.unpack_from(
            "<6I", data, phoff + i * phentsize
        )
        if kind == 1:  # PT_LOAD
            segments.append((vaddr, data[offset : offset + filesz], memsz))
    sections = [struct.unpack_from("<10I", data, shoff + i * shentsize) for i in range(shnum)]
    symbols = {}
    for section in sections:
        if section[1] != 2:  # SHT_SYMTAB
            continue
        strings = sections[section[6]][4]
        for k in range(section[5] // 16):
            name, value = struct.unpack_from("<II", data, section[4] + 16 * k)
            end = data.index(b"\0", strings + name)
            symbols[data[strings + name : end].decode()] = value & ~1  # no Thumb bit
    return Image(tuple(segments), symbols)


# ---- the episodes ----------------------------------------------------------------------------


class DumpedEpisode(NamedTuple):
    """One episode as ``ifgm_bench --dump`` wrote it: the raw structs of a float build."""

    episode: bytes
    tuning: bytes
    observations: tuple[bytes, ...]


def read_dump(path: Path) -> list[DumpedEpisode]:
    """The episodes of a ``ifgm_bench --dump`` file (format in ``examples/c/src/ifgm_bench.c``)."""
    data = path.read_bytes()
    if data[:8] != b"IFGMDUMP":
        raise ValueError(f"{path}: not an ifgm_bench dump")
    sizes = struct.unpack_from("<4i", data, 8)
    (episode, tuning, observation, count), at = sizes, 24
    episodes = []
    for _ in range(count):
        e, t = data[at : at + episode], data[at + episode : at + episode + tuning]
        at += episode + tuning
        (steps,) = struct.unpack_from("<i", data, at)
        at += 4
        obs = tuple(data[at + k * observation : at + (k + 1) * observation] for k in range(steps))
        at += steps * observation
        episodes.append(DumpedEpisode(e, t, obs))
    return episodes


# ---- the emulation -------------------------------------------------------------------------


class Decision(NamedTuple):
    """One emulated decision: its branch, and for a counted one its cycles and stack."""

    branch: str | None
    cycles: Cost | None
    stack: int | None


class Emulator:
    """A Cortex-M4F running one planner image; :meth:`decide` steps it (see the module
    docstring)."""

    def __init__(self, image: Image, name: str) -> None:
        unicorn, arm = _module("unicorn"), _module("unicorn.arm_const")
        self.uc = uc = unicorn.Uc(
            unicorn.UC_ARCH_ARM, unicorn.UC_MODE_THUMB | unicorn.UC_MODE_MCLASS
        )
        for address, data, size in image.segments:
            base, end = address & ~0xFFF, (address + size + 0xFFF) & ~0xFFF
            uc.mem_map(base, end - base)
            uc.mem_write(address, data)
        uc.mem_map(RETURN, 0x1000)
        self.init, self.step = image.symbols[f"{name}_init"], image.symbols[f"{name}_step"]
        # RAM: the stack, then the command, the episode, the tuning, the observation, the planner.
        self.stack_low, self.stack_top = RAM, RAM + STACK
        self.command = self.stack_top
        self.inputs = self.command + 0x100
        self.planner = self.inputs + 0x10000
        uc.mem_map(RAM, (self.planner - RAM + PLANNER_RAM + 0xFFFF) & ~0xFFFF)
        cpacr = uc.reg_read(arm.UC_ARM_REG_C1_C0_2)
        uc.reg_write(arm.UC_ARM_REG_C1_C0_2, cpacr | 0xF << 20)  # CP10, CP11: the FPU on
        uc.reg_write(arm.UC_ARM_REG_FPEXC, 1 << 30)
        self.blocks: dict[tuple[int, int], Block] = {}

    def _call(self, function: int, *args: int) -> int:
        arm = _module("unicorn.arm_const")
        for register, value in zip((arm.UC_ARM_REG_R0, arm.UC_ARM_REG_R1, arm.UC_ARM_REG_R2),
                                   args, strict=False):  # fmt: skip
            self.uc.reg_write(register, value)
        self.uc.reg_write(arm.UC_ARM_REG_SP, self.stack_top)
        self.uc.reg_write(arm.UC_ARM_REG_LR, RETURN | 1)
        self.uc.emu_start(function | 1, RETURN)
        return int(self.uc.reg_read(arm.UC_ARM_REG_R0))

    def start(self, episode: DumpedEpisode) -> int:
        """``NAME_init`` for the episode; its status."""
        self.uc.mem_write(self.inputs, episode.episode + episode.tuning)
        status = self._call(
            self.init, self.planner, self.inputs, self.inputs + len(episode.episode)
        )
        return status - (1 << 32) if status >= 1 << 31 else status

    def decide(self, observation: bytes, count: bool) -> Decision:
        """``NAME_step`` on ``observation``; with ``count``, its cycles and stack."""
        self.uc.mem_write(self.inputs, observation)
        if not count:
            self._call(self.step, self.command, self.planner, self.inputs)
            return Decision(self._branch(), None, None)
        self.uc.mem_write(self.stack_low, bytes([PAINT]) * STACK)
        with self._counting() as total:
            self._call(self.step, self.command, self.planner, self.inputs)
        painted = bytes(self.uc.mem_read(self.stack_low, STACK))
        stack = STACK - (len(painted) - len(painted.lstrip(bytes([PAINT]))))
        return Decision(self._branch(), Cost(*total), stack)

    def _branch(self) -> str | None:
        (pointer,) = struct.unpack("<I", self.uc.mem_read(self.command + 12, 4))
        if pointer == 0:
            return None
        return bytes(self.uc.mem_read(pointer, 48)).split(b"\0", 1)[0].decode()

    @contextmanager
    def _counting(self) -> Iterator[list[int]]:
        """Sum the blocks' costs into the yielded ``[nominal, low, high]`` while inside."""
        total = [0, 0, 0]
        last: list[Any] = [None, 0]  # the last block and where it ends

        def on_block(uc: Any, address: int, size: int, _: Any) -> None:
            previous, end = last
            if previous is not None and previous.branches and address != end:
                _add_refill(total)
            block = self.blocks.get((address, size))
            if block is None:
                block = self.blocks[address, size] = decode_block(
                    bytes(uc.mem_read(address, size)), address
                )
            total[0] += block.cost.nominal
            total[1] += block.cost.low
            total[2] += block.cost.high
            last[:] = [block, address + size]

        hook = self.uc.hook_add(_module("unicorn").UC_HOOK_BLOCK, on_block)
        self.uc.ctl_flush_tb()  # blocks translated without the hook would not call it
        try:
            yield total
        finally:
            self.uc.hook_del(hook)
            self.uc.ctl_flush_tb()
        _add_refill(total)  # the return to the caller


def _add_refill(total: list[int]) -> None:
    for i, refill in enumerate(REFILL):
        total[i] += refill
