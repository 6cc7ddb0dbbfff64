"""Leaf SDF elements to model dataclasses: geometry, surfaces, inertials, visuals, sensors, plugins, lights, physics.

Frame resolution is not done here: elements that carry a `<pose>` get a `to_link(pose, relative_to, element)`
callback from the loader that returns the pose in the owning link's frame.
"""

from __future__ import annotations

import dataclasses
import math
import re
from collections.abc import Callable
from pathlib import Path

from lxml import etree

from diffctl.description.mass_matrix import inertia_is_valid
from diffctl.description.missing_mesh import MeshNotFound
from diffctl.description.model import (
    AirPressureSpec,
    Box,
    CameraSpec,
    Capsule,
    Collision,
    Cylinder,
    Geometry,
    ImuSpec,
    Inertial,
    LidarSpec,
    Light,
    MagnetometerSpec,
    Mesh,
    NavSatSpec,
    Noise,
    Physics,
    Plane,
    Plugin,
    Sensor,
    Sphere,
    SphericalCoordinates,
    Surface,
    Visual,
)
from diffctl.description.pose import Pose, Vec3
from diffctl.description.resources import is_remote, resolve_uri
from diffctl.description.sdf_values import (
    Doc,
    Element,
    bool_value,
    child,
    child_text,
    children,
    color_value,
    element_path,
    fail,
    float_value,
    int_value,
    parse_floats,
    pose_child,
    required_attr,
    vec3_value,
)
from diffctl.description.urdf.meshes import pybullet_mesh
from diffctl.errors import DescriptionError, suggest

ToLink = Callable[[Pose, str | None, Element | None], Pose]

GEOMETRY_TAGS = ("box", "cylinder", "sphere", "capsule", "ellipsoid", "plane", "mesh")
MESH_SUFFIXES = (".obj", ".stl")  # what PyBullet turns into collision and visual shapes
CONVERTED_SUFFIXES = (".dae",)  # converted once to OBJ (urdf/meshes.py), as for URDF meshes
LIDAR_SENSOR_TYPES = ("gpu_lidar", "lidar", "gpu_ray", "ray")
CAMERA_SENSOR_TYPES = {
    "camera": "camera",
    "depth_camera": "depth_camera",
    "depth": "depth_camera",
    "rgbd_camera": "rgbd_camera",
    "rgbd": "rgbd_camera",
}
IMU_SENSOR_TYPES = ("imu",)
NOISE_TYPES = ("none", "gaussian", "gaussian_quantized")


def parse_geometry(doc: Doc, parent: Element) -> Geometry:
    geo = child(parent, "geometry")
    if geo is None:
        fail(doc, parent, f"<{parent.tag}> needs a <geometry>", hint="one of " + ", ".join(GEOMETRY_TAGS))
    shapes = [c for c in geo if isinstance(c.tag, str) and c.tag != "empty"]
    if len(shapes) != 1 or shapes[0].tag not in GEOMETRY_TAGS:
        found = ", ".join(f"<{c.tag}>" for c in shapes) or "nothing"
        hint = suggest(shapes[0].tag, GEOMETRY_TAGS) if len(shapes) == 1 else ""
        fail(doc, geo, f"<geometry> must hold exactly one of {', '.join(GEOMETRY_TAGS)}; found {found}{hint}")
    shape = shapes[0]
    tag = shape.tag
    if tag == "box":
        size_el = child(shape, "size")
        if size_el is None:
            fail(doc, shape, "<box> needs <size>x y z</size> (metres)")
        size = parse_floats(doc, size_el, 3)
        return Box((size[0], size[1], size[2]))
    if tag in ("cylinder", "capsule"):
        radius = float_value(doc, shape, "radius")
        length = float_value(doc, shape, "length")
        return Cylinder(radius, length) if tag == "cylinder" else Capsule(radius, length)
    if tag == "sphere":
        return Sphere(float_value(doc, shape, "radius"))
    if tag == "ellipsoid":
        radii_el = child(shape, "radii")
        if radii_el is None:
            fail(doc, shape, "<ellipsoid> needs <radii>a b c</radii> (metres)")
        radii = parse_floats(doc, radii_el, 3)
        from diffctl.description.generated_meshes import ellipsoid_obj

        uri = "ellipsoid://" + " ".join(f"{r:g}" for r in radii)
        solid = all(r > 0 for r in radii)  # a flat one is kept as written; the simulator leaves it out
        return Mesh(str(ellipsoid_obj((radii[0], radii[1], radii[2]))) if doc.check_files and solid else "", uri)
    if tag == "plane":
        normal = vec3_value(doc, shape, "normal", (0.0, 0.0, 1.0))
        n = math.sqrt(sum(c * c for c in normal))
        if n == 0:
            fail(doc, child(shape, "normal"), "<normal> of a plane must not be the zero vector")
        size_el = child(shape, "size")
        size = (100.0, 100.0)
        if size_el is not None:
            size = tuple(abs(s) for s in parse_floats(doc, size_el, 2))  # (sdformat checks no vector's range)
        return Plane((normal[0] / n, normal[1] / n, normal[2] / n), (size[0], size[1]))
    return _parse_mesh(doc, shape)


def _parse_mesh(doc: Doc, shape: Element) -> Mesh:
    uri_el = child(shape, "uri")
    uri = (uri_el.text or "").strip() if uri_el is not None else ""
    if not uri:
        fail(doc, shape, "<mesh> needs a <uri>")
    scale = vec3_value(doc, shape, "scale", (1.0, 1.0, 1.0))
    path = _fuel_file(doc, uri, uri_el) if is_remote(uri) else resolve_uri(uri, doc.base_dir, doc.search_path)
    if path is None or not path.is_file():
        if doc.check_files:
            raise MeshNotFound(
                f"mesh {uri!r} not found",
                source=doc.source,
                line=uri_el.sourceline,
                field=element_path(uri_el),
                hint="searched "
                + ", ".join(str(d) for d in (doc.base_dir, *doc.search_path))
                + "; set GZ_SIM_RESOURCE_PATH",
            )
        return Mesh("", uri, scale)
    suffix = path.suffix.lower()
    if suffix in CONVERTED_SUFFIXES:
        if not doc.check_files:
            return Mesh("", uri, scale)  # TF and outlines do not need the mesh itself: no conversion
        from diffctl.description.urdf.meshes import convert_to_obj

        try:  # the same COLLADA → OBJ path URDF meshes take
            return Mesh(str(pybullet_mesh(convert_to_obj(path)) or ""), uri, scale)
        except DescriptionError as e:
            why = e.message.rpartition("cannot be read: ")[2]
            fail(doc, uri_el, f"mesh {uri!r} ({path}) cannot be read: {why}")
    if suffix not in MESH_SUFFIXES:
        if doc.check_files:
            hint = "supported: " + ", ".join(MESH_SUFFIXES + CONVERTED_SUFFIXES) + " (convert it, e.g. with Blender)"
            fail(doc, uri_el, f"mesh {uri!r} has format {path.suffix!r}", hint=hint)
        return Mesh("", uri, scale)  # TF and outlines do not need the mesh itself
    if not doc.check_files:
        return Mesh(str(path), uri, scale)
    try:  # an ASCII STL is converted; a mesh with no triangle keeps no file (the simulator leaves it out)
        usable = pybullet_mesh(path)
    except DescriptionError as e:
        why = e.message.rpartition("cannot be read: ")[2]
        fail(doc, uri_el, f"mesh {uri!r} ({path}) cannot be read: {why}")
    return Mesh(str(usable or ""), uri, scale)


def _fuel_file(doc: Doc, uri: str, uri_el: Element) -> Path | None:
    """A mesh given as a Fuel file URL (what a downloaded model's FixPaths wrote), from the Fuel cache."""
    from diffctl.fuel.resolve import FuelModelUnavailable, resolve_fuel

    try:
        path = resolve_fuel(uri)
    except DescriptionError as e:
        if not doc.check_files:
            return None
        what = e.message if isinstance(e, FuelModelUnavailable) else f"mesh {uri!r}: {e.message}"
        fail(doc, uri_el, what, hint=e.hint)
    if path is None and doc.check_files:
        fail(
            doc, uri_el, f"mesh {uri!r} is remote", hint="only Fuel model file URLs are fetched; refer to a local file"
        )
    return path


def parse_surface(doc: Doc, collision: Element) -> Surface:
    surface = child(collision, "surface")
    if surface is None:
        return Surface()
    mu, mu2, restitution = 1.0, 1.0, 0.0
    friction = child(surface, "friction")
    if friction is not None:
        ode = child(friction, "ode")
        if ode is not None:
            mu = float_value(doc, ode, "mu", 1.0, minimum=0.0, allow_inf=True)
            mu2 = float_value(doc, ode, "mu2", mu, minimum=0.0, allow_inf=True)
        else:
            bullet = child(friction, "bullet")
            if bullet is not None:
                mu = float_value(doc, bullet, "friction", 1.0, minimum=0.0)
                mu2 = float_value(doc, bullet, "friction2", mu, minimum=0.0)
    bounce = child(surface, "bounce")
    if bounce is not None:
        restitution = float_value(doc, bounce, "restitution_coefficient", 0.0, minimum=0.0)
    return Surface(mu, mu2, restitution)


def parse_collision(doc: Doc, el: Element, to_link: ToLink) -> Collision:
    name = required_attr(doc, el, "name")
    pose, rel, pose_el = pose_child(doc, el)
    pose_link = to_link(pose, rel, pose_el)
    surface = parse_surface(doc, el)
    fdir = _fdir1(doc, el, to_link, pose_link)
    if fdir is not None:
        surface = dataclasses.replace(surface, fdir1=fdir)
    return Collision(name, pose_link, parse_geometry(doc, el), surface)


def _fdir1(doc: Doc, collision: Element, to_link: ToLink, pose_link: Pose) -> Vec3 | None:
    """`<surface><friction><ode><fdir1 gz:expressed_in="frame">x y z</fdir1>` in the link frame: in the named
    frame (as it stands at load time), else in the collision's own frame (ODE's rule)."""
    ode = collision
    for tag in ("surface", "friction", "ode", "fdir1"):
        found = child(ode, tag)
        if found is None:
            return None
        ode = found
    x, y, z = parse_floats(doc, ode, 3)
    if x == y == z == 0.0:
        return None  # ODE's "no direction"
    # gz:expressed_in, with the gz prefix declared or not
    frame = next((v for k, v in ode.attrib.items() if re.split("[}:]", str(k))[-1] == "expressed_in"), "")
    rotation = to_link(Pose(), frame.strip(), ode) if frame.strip() else pose_link
    return rotation.rotate((x, y, z))


def parse_visual(doc: Doc, el: Element, to_link: ToLink) -> Visual:
    name = required_attr(doc, el, "name")
    pose, rel, pose_el = pose_child(doc, el)
    rgba = None
    material = child(el, "material")
    if material is not None:
        rgba = color_value(doc, material, "diffuse", None) or color_value(doc, material, "ambient", None)
    retro = float_value(doc, el, "laser_retro", 0.0) if child(el, "laser_retro") is not None else 0.0
    return Visual(name, to_link(pose, rel, pose_el), parse_geometry(doc, el), rgba, retro)


def parse_inertial(doc: Doc, el: Element, to_link: ToLink) -> Inertial:
    mass = float_value(doc, el, "mass", 1.0)
    pose, rel, pose_el = pose_child(doc, el)
    inertia = child(el, "inertia")
    values = {"ixx": 1.0, "ixy": 0.0, "ixz": 0.0, "iyy": 1.0, "iyz": 0.0, "izz": 1.0}
    if inertia is not None:
        for key, default in values.items():
            values[key] = float_value(doc, inertia, key, default)
    if not doc.kinematics_only and not inertia_is_valid(mass, **values):
        link = el.getparent()
        name = link.get("name") if link is not None else "?"
        shown = ", ".join(f"{k} {v:g}" for k, v in values.items())
        fail(
            doc,
            inertia if inertia is not None else el,
            f"A link named {name} has invalid inertia (sdformat's check): mass {mass:g}, {shown}",
            hint="the mass must not be negative and the inertia matrix positive semi-definite, its principal "
            "moments obeying the triangle inequality (zeros are fine)",
        )
    return Inertial(mass, to_link(pose, rel, pose_el), **values)


def parse_noise(doc: Doc, parent: Element | None) -> Noise:
    el = child(parent, "noise") if parent is not None else None
    if el is None:
        return Noise()
    kind = (el.get("type") or child_text(el, "type") or "none").strip().lower()
    if kind not in NOISE_TYPES:
        fail(
            doc,
            el,
            f"noise type {kind!r} is not valid{suggest(kind, NOISE_TYPES)}",
            hint="valid: " + ", ".join(NOISE_TYPES),
        )
    return Noise(
        kind,
        float_value(doc, el, "mean", 0.0),
        float_value(doc, el, "stddev", 0.0, minimum=0.0),
        float_value(doc, el, "bias_mean", 0.0),
        float_value(doc, el, "bias_stddev", 0.0, minimum=0.0),
    )


def _parse_lidar(doc: Doc, sensor: Element) -> LidarSpec:
    body = child(sensor, "lidar")
    if body is None:
        body = child(sensor, "ray")
    if body is None:
        fail(doc, sensor, f"a {sensor.get('type')} sensor needs a <lidar> element with <scan> and <range>")
    scan = child(body, "scan")
    horizontal = child(scan, "horizontal") if scan is not None else None
    vertical = child(scan, "vertical") if scan is not None else None
    h = _scan_axis(doc, horizontal, 640)
    v = _scan_axis(doc, vertical, 1)
    rng = child(body, "range")
    if rng is None:
        fail(doc, body, f"<{body.tag}> needs <range> with <min> and <max> (metres)")
    range_min = float_value(doc, rng, "min", 0.0, minimum=0.0)
    range_max = float_value(doc, rng, "max", positive=True)
    if range_max <= range_min:
        fail(doc, rng, f"<range> <max> {range_max:g} must exceed <min> {range_min:g}")
    return LidarSpec(
        horizontal_samples=h[0],
        horizontal_resolution=h[1],
        horizontal_min_angle_rad=h[2],
        horizontal_max_angle_rad=h[3],
        vertical_samples=v[0],
        vertical_resolution=v[1],
        vertical_min_angle_rad=v[2],
        vertical_max_angle_rad=v[3],
        range_min_m=range_min,
        range_max_m=range_max,
        range_resolution_m=float_value(doc, rng, "resolution", 0.0, minimum=0.0),
        noise=parse_noise(doc, body),
    )


def _scan_axis(doc: Doc, el: Element | None, samples_default: int) -> tuple[int, float, float, float]:
    if el is None:
        return (samples_default, 1.0, 0.0, 0.0)
    samples = int_value(doc, el, "samples", samples_default, minimum=1)
    resolution = float_value(doc, el, "resolution", 1.0, positive=True)
    lo = float_value(doc, el, "min_angle", 0.0)
    hi = float_value(doc, el, "max_angle", 0.0)
    if hi < lo:
        fail(doc, el, f"<max_angle> {hi:g} is below <min_angle> {lo:g}")
    return (samples, resolution, lo, hi)


# sdformat's defaults (sdf/1.11/camera.sdf) for what a given <intrinsics> / <projection> leaves out.
def _lens_intrinsics(doc: Doc, el: Element | None) -> tuple[float, float, float, float, float] | None:
    if el is None:
        return None
    fx, fy = float_value(doc, el, "fx", 277.0, positive=True), float_value(doc, el, "fy", 277.0, positive=True)
    return (
        fx,
        fy,
        float_value(doc, el, "cx", 160.0),
        float_value(doc, el, "cy", 120.0),
        float_value(doc, el, "s", 0.0),
    )


def _lens_projection(doc: Doc, el: Element | None) -> tuple[float, float, float, float, float, float] | None:
    if el is None:
        return None
    return (
        float_value(doc, el, "p_fx", 277.0, positive=True),
        float_value(doc, el, "p_fy", 277.0, positive=True),
        float_value(doc, el, "p_cx", 160.0),
        float_value(doc, el, "p_cy", 120.0),
        float_value(doc, el, "tx", 0.0),
        float_value(doc, el, "ty", 0.0),
    )


def _distortion(doc: Doc, el: Element | None) -> tuple[float, float, float, float, float]:
    if el is None:
        return (0.0, 0.0, 0.0, 0.0, 0.0)
    k1, k2, k3 = (float_value(doc, el, t, 0.0) for t in ("k1", "k2", "k3"))
    return (k1, k2, float_value(doc, el, "p1", 0.0), float_value(doc, el, "p2", 0.0), k3)


def _optional_positive(doc: Doc, el: Element | None, tag: str) -> float | None:
    return float_value(doc, el, tag, positive=True) if el is not None and child(el, tag) is not None else None


def _parse_camera(doc: Doc, sensor: Element) -> CameraSpec:
    cam = child(sensor, "camera")
    if cam is None:
        fail(doc, sensor, "a camera sensor needs a <camera> element")
    hfov = float_value(doc, cam, "horizontal_fov", 1.047, positive=True)
    if hfov >= math.pi:
        fail(doc, child(cam, "horizontal_fov"), f"<horizontal_fov> must be below pi (radians), got {hfov:g}")
    image = child(cam, "image")
    width, height, fmt = 320, 240, "R8G8B8"
    if image is not None:
        width = int_value(doc, image, "width", 320, minimum=1)
        height = int_value(doc, image, "height", 240, minimum=1)
        fmt = child_text(image, "format", "R8G8B8") or "R8G8B8"
    clip = child(cam, "clip")
    near, far = 0.1, 100.0
    if clip is not None:
        near = float_value(doc, clip, "near", 0.1, positive=True)
        far = float_value(doc, clip, "far", 100.0, positive=True)
        if far <= near:
            fail(doc, clip, f"<clip> <far> {far:g} must exceed <near> {near:g}")
    info_topic = child_text(cam, "camera_info_topic")
    lens = child(cam, "lens")
    depth_camera = child(cam, "depth_camera")
    depth_clip = child(depth_camera, "clip") if depth_camera is not None else None
    trigger_topic = child_text(cam, "trigger_topic")
    return CameraSpec(
        width,
        height,
        hfov,
        fmt,
        near,
        far,
        parse_noise(doc, cam),
        camera_info_topic="/" + info_topic.lstrip("/") if info_topic else "",
        optical_frame_id=child_text(cam, "optical_frame_id") or "",
        lens_intrinsics_px=_lens_intrinsics(doc, child(lens, "intrinsics") if lens is not None else None),
        lens_projection_px=_lens_projection(doc, child(lens, "projection") if lens is not None else None),
        distortion=_distortion(doc, child(cam, "distortion")),
        depth_clip_m=(_optional_positive(doc, depth_clip, "near"), _optional_positive(doc, depth_clip, "far")),
        triggered=bool_value(doc, cam, "triggered", False),
        trigger_topic="/" + trigger_topic.strip().lstrip("/") if trigger_topic and trigger_topic.strip() else "",
    )


def _parse_imu(doc: Doc, sensor: Element) -> ImuSpec:
    imu = child(sensor, "imu")
    if imu is None:
        return ImuSpec()

    def axes(tag: str) -> tuple[Noise, Noise, Noise]:
        group = child(imu, tag)
        if group is None:
            return (Noise(), Noise(), Noise())
        return (
            parse_noise(doc, child(group, "x")),
            parse_noise(doc, child(group, "y")),
            parse_noise(doc, child(group, "z")),
        )

    return ImuSpec(axes("angular_velocity"), axes("linear_acceleration"))


def _parse_air_pressure(doc: Doc, sensor: Element) -> AirPressureSpec:
    el = child(sensor, "air_pressure")
    if el is None:
        return AirPressureSpec()
    pressure = child(el, "pressure")
    return AirPressureSpec(float_value(doc, el, "reference_altitude", 0.0), parse_noise(doc, pressure))


def _parse_magnetometer(doc: Doc, sensor: Element) -> MagnetometerSpec:
    el = child(sensor, "magnetometer")
    if el is None:
        return MagnetometerSpec()
    x, y, z = (parse_noise(doc, child(el, axis)) for axis in ("x", "y", "z"))
    return MagnetometerSpec((x, y, z))


def _parse_navsat(doc: Doc, sensor: Element) -> NavSatSpec:
    el = child(sensor, "navsat")
    if el is None:
        el = child(sensor, "gps")
    if el is None:
        return NavSatSpec()

    def noise(group: str, axis: str) -> Noise:
        g = child(el, group)
        a = child(g, axis) if g is not None else None
        return parse_noise(doc, a) if a is not None else Noise()

    return NavSatSpec(
        noise("position_sensing", "horizontal"),
        noise("position_sensing", "vertical"),
        noise("velocity_sensing", "horizontal"),
        noise("velocity_sensing", "vertical"),
    )


def parse_spherical_coordinates(doc: Doc, world: Element) -> SphericalCoordinates | None:
    el = child(world, "spherical_coordinates")
    if el is None:
        return None
    return SphericalCoordinates(
        latitude_deg=float_value(doc, el, "latitude_deg", 0.0),
        longitude_deg=float_value(doc, el, "longitude_deg", 0.0),
        elevation_m=float_value(doc, el, "elevation", 0.0),
        heading_deg=float_value(doc, el, "heading_deg", 0.0),
        surface_model=(child_text(el, "surface_model") or "EARTH_WGS84").strip(),
        world_frame_orientation=(child_text(el, "world_frame_orientation") or "ENU").strip(),
    )


def sensor_kind(sdf_type: str) -> str | None:
    if sdf_type in LIDAR_SENSOR_TYPES:
        return "lidar"
    if sdf_type in CAMERA_SENSOR_TYPES:
        return CAMERA_SENSOR_TYPES[sdf_type]
    if sdf_type in IMU_SENSOR_TYPES:
        return "imu"
    if sdf_type == "air_pressure":
        return "air_pressure"
    if sdf_type in ("navsat", "gps"):  # sdformat reads the old "gps" as navsat
        return "navsat"
    if sdf_type == "magnetometer":
        return "magnetometer"
    return None


def parse_sensor(doc: Doc, el: Element, link: str, to_link: ToLink, link_world: Pose) -> Sensor | None:
    """The sensor, or None for a type diffctl does not simulate (the loader lists those as ignored)."""
    name = required_attr(doc, el, "name")
    sdf_type = required_attr(doc, el, "type")
    kind = sensor_kind(sdf_type)
    if kind is None:
        return None
    pose, rel, pose_el = pose_child(doc, el)
    pose_link = to_link(pose, rel, pose_el)
    # gz-transport makes relative topic names absolute; consumers get one spelling. Without <topic> Gazebo
    # derives one from the world's name, which a model file alone does not know: the simulator does that.
    given = child_text(el, "topic")
    topic = "/" + given.lstrip("/") if given else ""
    frame_id = child_text(el, "gz_frame_id") or child_text(el, "frame_id") or None
    return Sensor(
        name=name,
        type=kind,
        sdf_type=sdf_type,
        link=link,
        topic=topic,
        update_rate_hz=float_value(doc, el, "update_rate", 0.0, minimum=0.0),
        always_on=bool_value(doc, el, "always_on", False),
        visualize=bool_value(doc, el, "visualize", False),
        pose_link=pose_link,
        pose_world=link_world.compose(pose_link),
        frame_id=frame_id,
        lidar=_parse_lidar(doc, el) if kind == "lidar" else None,
        camera=_parse_camera(doc, el) if kind in ("camera", "depth_camera", "rgbd_camera") else None,
        imu=_parse_imu(doc, el) if kind == "imu" else None,
        air_pressure=_parse_air_pressure(doc, el) if kind == "air_pressure" else None,
        navsat=_parse_navsat(doc, el) if kind == "navsat" else None,
        magnetometer=_parse_magnetometer(doc, el) if kind == "magnetometer" else None,
    )


def parse_plugin(doc: Doc, el: Element) -> Plugin:
    filename = required_attr(doc, el, "filename")
    params = tuple((str(c.tag), (c.text or "").strip()) for c in el if isinstance(c.tag, str))
    xml = etree.tostring(el, encoding="unicode", with_tail=False)
    return Plugin((el.get("name") or "").strip(), filename, params, xml)


LIGHT_TYPES = ("directional", "point", "spot")


def parse_light(doc: Doc, el: Element, parent_world: Pose) -> Light:
    name = required_attr(doc, el, "name")
    kind = (el.get("type") or "point").strip()
    if kind not in LIGHT_TYPES:
        fail(
            doc,
            el,
            f"light type {kind!r} is not valid{suggest(kind, LIGHT_TYPES)}",
            hint="valid: " + ", ".join(LIGHT_TYPES),
        )
    pose, _, _ = pose_child(doc, el)
    return Light(
        name=name,
        type=kind,
        pose_world=parent_world.compose(pose),
        direction=vec3_value(doc, el, "direction", (0.0, 0.0, -1.0)),
        diffuse=color_value(doc, el, "diffuse", (1.0, 1.0, 1.0, 1.0)) or (1.0, 1.0, 1.0, 1.0),
        specular=color_value(doc, el, "specular", (0.1, 0.1, 0.1, 1.0)) or (0.1, 0.1, 0.1, 1.0),
        cast_shadows=bool_value(doc, el, "cast_shadows", False),
    )


def parse_physics(doc: Doc, world: Element) -> Physics:
    """The world's <physics> (the one marked default="true", else the first) and <gravity>."""
    candidates = children(world, "physics")
    el = next((p for p in candidates if (p.get("default") or "").strip().lower() in ("true", "1")), None)
    if el is None and candidates:
        el = candidates[0]
    gravity_parent = world if child(world, "gravity") is not None else (el if el is not None else world)
    gravity = vec3_value(doc, gravity_parent, "gravity", (0.0, 0.0, -9.8))
    magnetic = vec3_value(doc, world, "magnetic_field", Physics().magnetic_field_t)
    if el is None:
        return Physics(gravity=gravity, magnetic_field_t=magnetic)
    return Physics(
        max_step_size_s=float_value(doc, el, "max_step_size", 0.001, positive=True),
        real_time_factor=float_value(doc, el, "real_time_factor", 1.0, minimum=0.0),
        gravity=gravity,
        real_time_update_rate_hz=float_value(doc, el, "real_time_update_rate", 1000.0, minimum=0.0),
        magnetic_field_t=magnetic,
    )
