"""Test vectors: equation test vectors and reference traces in one JSON file.

For implementations that cannot run Python -- a microcontroller C port, say -- the oracle's
checks are written down as data: ``ifgm-ref vectors --out vectors.json`` writes

* **equation vectors**: inputs of every function of :mod:`ifgm_ref.paper.equations` with the output
  of the printed (*literal*) and of the interpreted form, or the error each raises: hand-picked
  cases for every errata row that touches an equation (``docs/errata.md``) and seeded random
  ones;
* **reference traces**: short IFGM and IBA episodes in built-in worlds, each step's
  observation exactly as the JSON-lines protocol sends it (:mod:`ifgm_ref.io.transport.wire`) with
  the command the reference planner answered, together covering every branch of Figure 3.

``docs/vectors-format.md`` specifies the file. The same data checks Python implementations:
:func:`check_vectors` runs any object with the equation functions' names against the vectors,
:func:`replay_traces` steps a planner through the traces; both answer a list of mismatches in
the oracle's ``quantity = actual, but should be expected [where]`` style.

==============  ==============================================================================
module          what it holds
==============  ==============================================================================
``schema``      the file's parts as frozen dataclasses, written to JSON and read back
``tolerances``  every compared quantity with its double and float32 tolerances and why
``cases``       the equation groups with their hand-picked cases and random draws; the traces
``build``       evaluating the cases, running the traces, writing the file
``check``       checking an implementation's equations and replaying a planner on the traces
==============  ==============================================================================
"""

from __future__ import annotations

from ifgm_ref.oracle.vectors.build import (
    VectorsSummary,
    build_document,
    build_vectors,
    dumps_vectors,
    summarize,
    write_vectors,
)
from ifgm_ref.oracle.vectors.cases import (
    GROUPS,
    RANDOM_CASES,
    TRACES,
    Case,
    EquationGroup,
    TraceSpec,
)
from ifgm_ref.oracle.vectors.check import check_vectors, replay_traces
from ifgm_ref.oracle.vectors.schema import (
    FORMAT_NAME,
    FORMAT_VERSION,
    PRECISIONS,
    Form,
    Quantity,
    Tolerance,
    VectorsDocument,
)
from ifgm_ref.oracle.vectors.tolerances import QUANTITIES

__all__ = [
    "FORMAT_NAME",
    "FORMAT_VERSION",
    "GROUPS",
    "PRECISIONS",
    "QUANTITIES",
    "RANDOM_CASES",
    "TRACES",
    "Case",
    "EquationGroup",
    "Form",
    "Quantity",
    "Tolerance",
    "TraceSpec",
    "VectorsDocument",
    "VectorsSummary",
    "build_document",
    "build_vectors",
    "check_vectors",
    "dumps_vectors",
    "replay_traces",
    "summarize",
    "write_vectors",
]
