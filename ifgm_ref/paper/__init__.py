"""The paper, as code: equations (1)-(4) (:mod:`.equations`), Figure 3's flowchart
(:mod:`.flowchart`), the percepts a planner forms from one scan (:mod:`.percepts`), and the
traceability matrix that ties code to the paper's elements (:mod:`.traceability`).

Imports :mod:`ifgm_ref.core` only: no planner, no world.
"""
