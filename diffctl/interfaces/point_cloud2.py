"""sensor_msgs_py.point_cloud2 (Jazzy's API): PointCloud2 messages to and from numpy arrays and point tuples.

A cloud's bytes are viewed as a structured numpy array whose dtype comes from its PointFields (a field with
count n becomes n subfields `name_0 … name_{n-1}`, an unnamed one `unnamed_field_<i>`); assertion messages
are sensor_msgs_py's. The message classes are imported from `sensor_msgs.msg` like any user's, so a real
ROS's packages, where they come first on sys.path, are used alike.
"""

from __future__ import annotations

import array
import sys
from collections import namedtuple
from collections.abc import Iterable
from typing import Any

import numpy as np
from numpy.lib.recfunctions import structured_to_unstructured, unstructured_to_structured

DUMMY_FIELD_PREFIX = "unnamed_field"
# PointField's datatype constants (INT8 = 1 … FLOAT64 = 8) → numpy dtypes
_DTYPES = {1: np.dtype(np.int8), 2: np.dtype(np.uint8), 3: np.dtype(np.int16), 4: np.dtype(np.uint16),
           5: np.dtype(np.int32), 6: np.dtype(np.uint32), 7: np.dtype(np.float32), 8: np.dtype(np.float64)}


def _classes() -> tuple[type, type]:
    from sensor_msgs.msg import PointCloud2, PointField

    return PointCloud2, PointField


def dtype_from_fields(fields: Iterable[Any], point_step: int | None = None) -> np.dtype:
    """The structured dtype of a cloud's points, from its PointFields (and point_step as the item size)."""
    names: list[str] = []
    offsets: list[int] = []
    formats: list[str] = []
    for i, field in enumerate(fields):
        dtype = _DTYPES[field.datatype]
        name = field.name if field.name != "" else f"{DUMMY_FIELD_PREFIX}_{i}"
        assert field.count > 0, "Can't process fields with count = 0."
        for k in range(field.count):
            sub = f"{name}_{k}" if field.count > 1 else name
            assert sub not in names, "Duplicate field names are not allowed!"
            names.append(sub)
            offsets.append(field.offset + k * dtype.itemsize)
            formats.append(dtype.str)
    spec: dict[str, Any] = {"names": names, "formats": formats, "offsets": offsets}
    if point_step is not None:
        spec["itemsize"] = point_step
    return np.dtype(spec)


def read_points(cloud: Any, field_names: list[str] | None = None, skip_nans: bool = False,
                uvs: Iterable | None = None, reshape_organized_cloud: bool = False) -> np.ndarray:
    """The cloud's points as a structured array (a view of its data where no selection copies it)."""
    assert isinstance(cloud, _classes()[0]), "Cloud is not a sensor_msgs.msg.PointCloud2"
    points = np.ndarray(shape=(cloud.width * cloud.height,),
                        dtype=dtype_from_fields(cloud.fields, point_step=cloud.point_step), buffer=cloud.data)
    if field_names is not None:
        assert all(name in points.dtype.names for name in field_names), \
            "Requests field is not in the fields of the PointCloud!"
        points = points[list(field_names)]
    if (sys.byteorder != "little") != bool(cloud.is_bigendian):
        points = points.byteswap(inplace=True)
    if skip_nans and not cloud.is_dense:
        keep = np.ones(len(points), dtype=bool)
        for name in points.dtype.names:
            keep &= ~np.isnan(points[name])
        points = points[keep]
    if uvs is not None:
        points = points[uvs if isinstance(uvs, np.ndarray) else np.fromiter(uvs, int)]
    if reshape_organized_cloud and cloud.height > 1:
        # sensor_msgs_py's shape: (width, height)
        points = points.reshape(cloud.width, cloud.height)
    return points


def read_points_numpy(cloud: Any, field_names: list[str] | None = None, skip_nans: bool = False,
                      uvs: Iterable | None = None, reshape_organized_cloud: bool = False) -> np.ndarray:
    """The selected fields (all of one datatype) as a plain 2-D array, one row per point."""
    assert all(cloud.fields[0].datatype == f.datatype for f in cloud.fields[1:]
               if field_names is None or f.name in field_names), \
        "All fields need to have the same datatype. Use `read_points()` otherwise."
    return structured_to_unstructured(read_points(cloud, field_names, skip_nans, uvs, reshape_organized_cloud))


def read_points_list(cloud: Any, field_names: list[str] | None = None, skip_nans: bool = False,
                     uvs: Iterable | None = None) -> list[Any]:
    """The points as a list of namedtuples `Point(x=…, …)`."""
    assert isinstance(cloud, _classes()[0]), "cloud is not a sensor_msgs.msg.PointCloud2"
    if field_names is None:
        field_names = [f.name for f in cloud.fields]
    point = namedtuple("Point", field_names)
    return [point._make(p) for p in read_points(cloud, field_names, skip_nans, uvs)]


def create_cloud(header: Any, fields: Any, points: Iterable, point_step: int | None = None) -> Any:
    """A PointCloud2 of `points`: a structured or plain numpy array, or an iterable of per-point iterables;
    a 2-D array of points makes an organized cloud."""
    cloud_cls, _ = _classes()
    if isinstance(points, np.ndarray):
        if points.dtype.names is None:
            assert all(fields[0].datatype == f.datatype for f in fields[1:]), \
                "All fields need to have the same datatype. Pass a structured NumPy array \
                    with multiple dtypes otherwise."
            points = unstructured_to_structured(points, dtype=dtype_from_fields(fields, point_step))
        else:
            assert points.dtype == dtype_from_fields(fields, point_step), \
                "PointFields and structured NumPy array dtype do not match for all fields! \
                    Check their field order, names and types."
    else:
        points = np.array([tuple(p) for p in points], dtype=dtype_from_fields(fields, point_step))
    assert len(points.shape) <= 2, \
        "Too many dimensions for organized cloud! \
            Points can only be organized in max. two dimensional space"
    width = points.shape[0]
    height = points.shape[1] if len(points.shape) == 2 else 1
    data = array.array("B")
    data.frombytes(memoryview(points).cast("B"))
    cloud = cloud_cls(header=header, height=height, width=width, is_dense=False,
                      is_bigendian=sys.byteorder != "little", fields=fields, point_step=points.dtype.itemsize,
                      row_step=points.dtype.itemsize * width)
    cloud.data = data
    return cloud


def create_cloud_xyz32(header: Any, points: Iterable) -> Any:
    """A PointCloud2 with float32 x, y and z fields."""
    _, field_cls = _classes()
    fields = [field_cls(name=n, offset=4 * i, datatype=7, count=1) for i, n in enumerate("xyz")]
    return create_cloud(header, fields, points)
