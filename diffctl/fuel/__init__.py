"""Gazebo Fuel models as gz-fuel-tools finds them: URIs, the local cache layout, known scenery, REST download.

`resolve_model(uri)` is the one entry point the SDF loader calls for an `<include><uri>https://fuel…`:
Gazebo's own cache first, then the scenery every world includes (ground plane, sun) shipped with diffctl,
then a download into the same cache when the network allows.
"""
