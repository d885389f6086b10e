"""The report room: the jobs' data in, results.json, REPORT.md, report.html, the conservation table
and the figures out (:func:`verify.report.write.write_report`).

This file imports nothing: a job that uses one module of the room (a figure renderer) must not
depend, through the package, on the whole room (:mod:`.dependencies` counts a package's
``__init__`` and what it imports).
"""
