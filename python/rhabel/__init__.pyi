# Type stubs of the package rhabel (the implementation: __init__.py and the extension _rhabel).
from os import PathLike
from typing import IO, Any, Literal, Mapping, NamedTuple, Sequence, Union, overload

import numpy as np
import numpy.typing as npt

from . import abel as abel
from . import riemann as riemann
from ._record import Contact as Contact
from ._record import Record as Record
from ._record import Result as Result

__version__: str
# Several points (a float alone is the other overload).
_Points = Union[Sequence[float], npt.NDArray[Any]]
__all__: list[str]

def solve(scene: Mapping[str, Any], grid: int = ..., displacement: bool = ..., tolerance: float = ...,
          residual: bool = ..., acceptance: float | None = ..., threads: int = ..., time_limit: float = ...,
          layered_below: float = ..., spacing: Literal["uniform", "graded"] = ...,
          profile_knots: bool = ...) -> Result: ...
def sweep(sweep: Union[Mapping[str, Any], str, PathLike[str]], out: Union[str, PathLike[str], None] = ...,
          threads: int = ..., progress: bool = ..., tolerance: float = ..., acceptance: float | None = ...,
          time_limit: float = ..., profile_knots: bool = ...) -> list[Record]: ...
def fit_material(curve: Union[str, PathLike[str]], speed: float, length: float, temperature: float | None = ...,
                 wlf: Union[Mapping[str, float], Sequence[float], None] = ..., window_decades: float = ...,
                 threshold: float = ...) -> Record: ...
def trial_interval(scene: Mapping[str, Any], a: float, b: float, tolerance: float = ...) -> Record: ...
def validate_scene(scene: Mapping[str, Any]) -> dict[str, Any]: ...
def load_scene(path: Union[str, PathLike[str], IO[str]]) -> dict[str, Any]: ...

class GaussJacobiRule(NamedTuple):
    x: npt.NDArray[np.float64]
    hi_minus_x: npt.NDArray[np.float64]
    x_minus_lo: npt.NDArray[np.float64]
    weight: npt.NDArray[np.float64]

def gauss_jacobi(n: int, p: float, q: float, lo: float = ..., hi: float = ...) -> GaussJacobiRule: ...
@overload
def jacobi_p(n: int, p: float, q: float, x: float) -> float: ...
@overload
def jacobi_p(n: int, p: float, q: float, x: _Points) -> npt.NDArray[np.float64]: ...
