from typing import Any, Sequence, Union, overload

import numpy as np
import numpy.typing as npt

class Record(dict[str, Any]):
    """A dict whose keys are also attributes (nested dicts are Records, sampled fields NumPy arrays)."""
    def __getattr__(self, name: str) -> Any: ...
    def to_dict(self) -> dict[str, Any]: ...
    def to_plain(self) -> dict[str, Any]: ...
    def to_json(self, **kwargs: Any) -> str: ...

class Contact(Record):
    """The Record of one contact, with its solved pressure as a function."""
    @overload
    def pressure_at(self, x: float) -> float: ...
    @overload
    def pressure_at(self, x: Union[Sequence[float], npt.NDArray[Any]]) -> npt.NDArray[np.float64]: ...

class Result(Record):
    """The Record of rhabel.solve; its repr is one line per contact."""
