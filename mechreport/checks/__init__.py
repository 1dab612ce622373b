"""Stage 5: checks on solved results: method agreement, equilibrium residuals, expectations."""
from .agreement import Agreement, agreement
from .expectations import ExpectationResult, check_expectations
from .residuals import Residual, residuals

__all__ = ["Agreement", "agreement", "ExpectationResult", "check_expectations", "Residual",
           "residuals"]
