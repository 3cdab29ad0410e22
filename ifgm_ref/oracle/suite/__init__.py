"""The conformance suite: the oracle's checks frozen as data, with stable case ids.

The drawn profiles (:mod:`ifgm_ref.oracle.profiles`) search; the suite decides. Each version
(``ifgm_ref/oracle/suite/v1/``) holds cases written once by ``ifgm-ref suite build`` and never
changed after: a case names its check, holds its example (the world, start and goal, robot,
sensor and whatever else the check's test takes), the flags it depends on, the reference's
verdict and a tier. ``ifgm-ref oracle --suite v1`` runs exactly those cases, with no drawing,
and writes one JSON line per case (:mod:`.results`); ``ifgm-ref report`` shows runs side by
side. docs/oracle.md, "The conformance suite", gives the versioning rules.
"""
