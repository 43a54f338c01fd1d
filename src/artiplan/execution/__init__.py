"""artiplan.execution: the closed loop (plan, dispatch, monitor, re-plan), its run log,
calibration of the gravity models against physics, and the fidelity experiment."""

from artiplan.execution.config import Intervention, LoopConfig
from artiplan.execution.loop import ClosedLoop, run_loop
from artiplan.execution.monitor import Monitor, Verdict, goal_errors
from artiplan.execution.predict import Prediction
from artiplan.execution.runlog import RUN_LOG_SCHEMA, SCHEMA_RUN_LOG, RunLog, schema_errors

__all__ = [
    "RUN_LOG_SCHEMA",
    "SCHEMA_RUN_LOG",
    "ClosedLoop",
    "Intervention",
    "LoopConfig",
    "Monitor",
    "Prediction",
    "RunLog",
    "Verdict",
    "goal_errors",
    "run_loop",
    "schema_errors",
]
