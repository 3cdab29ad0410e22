"""Executable sympy derivations: equations (1)-(4) of the IFGM paper, and what we run.

One module per equation (``proofs.eq1`` ... ``proofs.eq4``), and one each for the Figure 3
flowchart's guards (``proofs.flowchart``), the scale-free parameters (``proofs.scale``) and
the braking governor (``proofs.braking``, with ``proofs.braking_fan``). Each has

- ``derivation()``: builds the worked derivation, checking every claim as it goes; a claim
  sympy does not reduce to exactly 0 or True raises :class:`proofs._util.ClaimFailed`;
- ``claims()``: the checked claims, for the test suite (``tests/test_proofs.py``);
- ``main()``: prints the derivation as a worked page: ``python -m proofs.eq4``.

Claims are cited as ``proofs.eqN:claim_name`` (e.g. in ``docs/errata.md``). Claims of kind
``numeric spot check`` tie the sympy formulas to :mod:`ifgm_ref.paper.equations` at sample points;
they are regression tests, not proofs.
"""
