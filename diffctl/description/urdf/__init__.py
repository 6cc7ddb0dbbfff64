"""URDF robots as Gazebo simulates them: parse (urdfdom's rules), lump fixed joints, apply `<gazebo>` extensions,
convert to SDF and build the same `model.Model` the SDF loader gives; xacro runs through the `xacro` package.
"""
