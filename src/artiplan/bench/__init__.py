"""Benchmarks: suites x planners -> JSON Lines results -> Table 1, PAR10 and cactus reports.

- :mod:`suite`: read ``suite.json``; :mod:`jobs`: the one job function (plan, then validate);
- :mod:`run`: local pool or Dask cluster, resumable; :mod:`results`: the JSON Lines file;
- :mod:`report`: aggregate rows into the paper's tables and the comparisons.
"""
