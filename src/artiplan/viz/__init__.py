"""artiplan.viz: pictures (matplotlib, Agg backend), imported lazily by the commands.

Modules: ``draw`` (an articulated object in 3D, with a target ghost), ``trajectory`` (angles over
time), ``report`` (benchmark tables and plots). Importing this package imports no plotting code.
"""
