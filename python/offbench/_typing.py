"""The type aliases of the package's hints (PEP 484), in one place, in
typing's Python 3.8 spelling (no list[int], no X | Y: get_type_hints must
resolve them on every interpreter the package supports)."""

from typing import Any, Mapping, Sequence, Union

# a float, a sequence or an array of them (numpy.typing.ArrayLike's meaning;
# that module needs numpy 1.21, older than Debian's and conda's floors)
ArrayLike = Any

# pandas.DataFrame: pandas is optional (the [pandas] extra), so the hints do
# not import it
DataFrame = Any

# a method's parameters: {name: value} or "NAME=VALUE,..."
Params = Union[None, str, Mapping[str, float]]

# a number or a list of numbers (run's tols and d)
Numbers = Union[float, Sequence[float]]
