"""segplan: Campoy et al. (1989), trajectory planning for an oriented-segment robot."""

from .cost import longd_exact
from .pose import Pose
from .union import Union

__all__ = ["Pose", "Union", "longd_exact"]
