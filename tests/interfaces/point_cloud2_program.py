"""The sensor_msgs_py.point_cloud2 program of test_point_cloud2.py: run by make_runtime_golden.py under
upstream's sensor_msgs_py (common_interfaces, jazzy) with the real classes, and by the test under diffctl's."""

PROGRAM = r'''
import math
import numpy as np
from sensor_msgs.msg import PointCloud2, PointField
from std_msgs.msg import Header
from sensor_msgs_py import point_cloud2 as pc2

h = Header(frame_id='lidar')
xyz = pc2.create_cloud_xyz32(h, [[1.0, 2.0, 3.0], [4.0, 5.0, 6.0], [math.nan, 0.0, 1.0]])
obs('xyz cloud', lambda: xyz)
obs('read', lambda: pc2.read_points(xyz))
obs('read dtype', lambda: pc2.read_points(xyz).dtype)
obs('read fields', lambda: pc2.read_points(xyz, field_names=['x', 'z']))
obs('skip nans', lambda: pc2.read_points(xyz, skip_nans=True))
obs('uvs', lambda: pc2.read_points(xyz, uvs=[2, 0]))
obs('uvs numpy', lambda: pc2.read_points(xyz, uvs=np.array([1])))
obs('list', lambda: pc2.read_points_list(xyz))
obs('list fields', lambda: pc2.read_points_list(xyz, field_names=['y'], skip_nans=True))
obs('numpy', lambda: pc2.read_points_numpy(xyz))
obs('unknown field', lambda: pc2.read_points(xyz, field_names=['w']))
obs('not a cloud', lambda: pc2.read_points(h))
fields = [PointField(name='x', offset=0, datatype=PointField.FLOAT32, count=1),
          PointField(name='', offset=4, datatype=PointField.UINT8, count=1),
          PointField(name='rgb', offset=8, datatype=PointField.UINT16, count=3)]
obs('dtype', lambda: pc2.dtype_from_fields(fields))
obs('dtype step', lambda: pc2.dtype_from_fields(fields, point_step=32))
obs('dtype dup', lambda: pc2.dtype_from_fields([fields[0], fields[0]]))
obs('dtype count 0', lambda: pc2.dtype_from_fields([PointField(name='a', datatype=7, count=0)]))
mixed = pc2.create_cloud(h, fields, [(1.5, 7, 1, 2, 3), (2.5, 8, 4, 5, 6)])
obs('mixed', lambda: mixed)
obs('mixed read', lambda: pc2.read_points(mixed))
obs('mixed numpy', lambda: pc2.read_points_numpy(mixed))
obs('mixed numpy one', lambda: pc2.read_points_numpy(mixed, field_names=['x']))
arr = np.arange(12, dtype=np.float32).reshape(4, 3)
obs('from unstructured', lambda: pc2.create_cloud(h, xyz.fields, arr))
organized = np.zeros((2, 3), dtype=pc2.dtype_from_fields(xyz.fields))
org = pc2.create_cloud(h, xyz.fields, organized)
obs('organized', lambda: (org.height, org.width, org.row_step, org.point_step))
obs('organized read', lambda: pc2.read_points(org, reshape_organized_cloud=True).shape)
obs('structured mismatch', lambda: pc2.create_cloud(h, fields, organized))
obs('three dims', lambda: pc2.create_cloud(h, xyz.fields, np.zeros((1, 1, 1), dtype=organized.dtype)))
obs('mixed unstructured', lambda: pc2.create_cloud(h, fields, np.zeros((2, 5), dtype=np.float32)))
obs('dense', lambda: pc2.read_points(pc2.create_cloud_xyz32(h, [[math.nan, 1.0, 1.0]]), skip_nans=True))
obs('constants', lambda: pc2.DUMMY_FIELD_PREFIX)
'''
