"""Flight dynamics of the HiL simulator: a JSBSim model generated from aircraft/<name>/.

    from hil.fdm import Fdm, Truth, Surfaces, Wind
"""
from .fdm import Fdm, FdmCrash, TrimError
from .types import Surfaces, Truth, Wind

__all__ = ["Fdm", "FdmCrash", "TrimError", "Surfaces", "Truth", "Wind"]
