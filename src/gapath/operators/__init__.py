"""pymoo operators for grid paths: one operator per module."""

from gapath.operators.crossover.discrete_sbx import DiscreteSBX
from gapath.operators.crossover.mixed_crossover import MixedCrossover
from gapath.operators.defaults import default_operators
from gapath.operators.duplicates import PathDuplicateElimination
from gapath.operators.mutation.decaying_bitflip import DecayingBitflipMutation
from gapath.operators.mutation.discrete_pm import DiscretePM
from gapath.operators.mutation.mixed_mutation import MixedMutation
from gapath.operators.repair.edge_fixing import EdgeFixingRepair
from gapath.operators.repair.feasible import FeasibleStepRepair
from gapath.operators.sampling.free_sampling import FreeSampling
from gapath.operators.sampling.planner_sampling import PlannerSampling
from gapath.operators.selection.smoothness_tournament import (
    SmoothnessTournament,
    compare_rank_smoothness_crowding,
)
from gapath.operators.survival.rank_and_smoothness import RankAndSmoothnessSurvival, survival_order

__all__ = [
    "DecayingBitflipMutation",
    "DiscretePM",
    "DiscreteSBX",
    "EdgeFixingRepair",
    "FeasibleStepRepair",
    "FreeSampling",
    "MixedCrossover",
    "MixedMutation",
    "PathDuplicateElimination",
    "PlannerSampling",
    "RankAndSmoothnessSurvival",
    "SmoothnessTournament",
    "compare_rank_smoothness_crowding",
    "default_operators",
    "survival_order",
]
