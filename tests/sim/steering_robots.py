"""SDF robots for Gazebo's steering systems, written the way community robots write them: a car-like robot for
AckermannSteering (steering knuckles on revolute joints carrying the front wheels), a mecanum robot for
MecanumDrive (wheels whose contact has a friction direction `fdir1` with `mu2` 0, as gz-sim's example has) and
a tank for TrackedVehicle (track links fixed to the body, a TrackController each)."""

from __future__ import annotations

WHEEL_RADIUS_M = 0.1
WHEEL_BASE_M = 0.6  # front to rear axle
TRACK_M = 0.5  # left to right wheel centre (wheel_separation)
KINGPIN_M = 0.5
STEERING_LIMIT_RAD = 0.7


def _inertial(mass: float, i: float) -> str:
    return f"<inertial><mass>{mass}</mass><inertia><ixx>{i}</ixx><iyy>{i}</iyy><izz>{i}</izz></inertia></inertial>"


def _wheel_link(name: str, x: float, y: float, surface: str = "") -> str:
    return (
        f"<link name='{name}'><pose>{x} {y} {WHEEL_RADIUS_M} -1.5707963 0 0</pose>{_inertial(0.5, 0.003)}"
        f"<collision name='c'><geometry><sphere><radius>{WHEEL_RADIUS_M}</radius></sphere></geometry>{surface}"
        f"</collision><visual name='v'><geometry><cylinder><radius>{WHEEL_RADIUS_M}</radius><length>0.05</length>"
        "</cylinder></geometry></visual></link>"
    )


def _joint(name: str, kind: str, parent: str, child: str, axis: str, limit: str = "") -> str:
    return (
        f"<joint name='{name}' type='{kind}'><parent>{parent}</parent><child>{child}</child>"
        f"<axis><xyz expressed_in='__model__'>{axis}</xyz>{limit}</axis></joint>"
    )


def _chassis() -> str:
    return (
        f"<link name='chassis'><pose>{WHEEL_BASE_M / 2} 0 0.2 0 0 0</pose>{_inertial(10.0, 0.3)}"
        "<collision name='c'><geometry><box><size>0.8 0.4 0.1</size></box></geometry></collision>"
        "<visual name='v'><geometry><box><size>0.8 0.4 0.1</size></box></geometry></visual></link>"
    )


def ackermann_robot(name: str = "car", plugin_extra: str = "") -> str:
    """Rear-wheel drive; the rear axle centre is the model origin (where AckermannSteering's radius is taken)."""
    half = TRACK_M / 2
    links = [_chassis(), _wheel_link("rear_left", 0.0, half), _wheel_link("rear_right", 0.0, -half)]
    joints = [
        _joint("rear_left_joint", "continuous", "chassis", "rear_left", "0 1 0"),
        _joint("rear_right_joint", "continuous", "chassis", "rear_right", "0 1 0"),
    ]
    limit = f"<limit><lower>-{STEERING_LIMIT_RAD}</lower><upper>{STEERING_LIMIT_RAD}</upper></limit>"
    for side, y in (("left", half), ("right", -half)):
        links.append(
            f"<link name='{side}_knuckle'><pose>{WHEEL_BASE_M} {y} {WHEEL_RADIUS_M} 0 0 0</pose>"
            f"{_inertial(0.2, 0.001)}</link>"
        )
        links.append(_wheel_link(f"front_{side}", WHEEL_BASE_M, y))
        joints.append(_joint(f"{side}_steering_joint", "revolute", "chassis", f"{side}_knuckle", "0 0 1", limit))
        joints.append(_joint(f"front_{side}_joint", "continuous", f"{side}_knuckle", f"front_{side}", "0 1 0"))
    plugin = f"""<plugin filename="gz-sim-ackermann-steering-system" name="gz::sim::systems::AckermannSteering">
      <left_joint>rear_left_joint</left_joint><right_joint>rear_right_joint</right_joint>
      <left_steering_joint>left_steering_joint</left_steering_joint>
      <right_steering_joint>right_steering_joint</right_steering_joint>
      <kingpin_width>{KINGPIN_M}</kingpin_width><steering_limit>{STEERING_LIMIT_RAD}</steering_limit>
      <wheel_base>{WHEEL_BASE_M}</wheel_base><wheel_separation>{TRACK_M}</wheel_separation>
      <wheel_radius>{WHEEL_RADIUS_M}</wheel_radius><steer_p_gain>20</steer_p_gain>{plugin_extra}
    </plugin>"""
    return f"<model name='{name}'>{''.join(links)}{''.join(joints)}{plugin}</model>"


def mecanum_robot(name: str = "omni", plugin_extra: str = "") -> str:
    """Four wheels at the corners of a WHEEL_BASE_M × TRACK_M rectangle around the model origin; each wheel's
    contact grips only along its roller axis (fdir1 in the chassis frame, mu2 0)."""
    half_x, half_y = WHEEL_BASE_M / 2, TRACK_M / 2
    links = [_chassis().replace(f"<pose>{WHEEL_BASE_M / 2} 0 0.2 0 0 0</pose>", "<pose>0 0 0.2 0 0 0</pose>")]
    joints = []
    for wheel, x, y, fdir in (
        ("front_left", half_x, half_y, "1 -1 0"),
        ("front_right", half_x, -half_y, "1 1 0"),
        ("rear_left", -half_x, half_y, "1 1 0"),
        ("rear_right", -half_x, -half_y, "1 -1 0"),
    ):
        surface = (
            "<surface><friction><ode><mu>1.0</mu><mu2>0.0</mu2>"
            f"<fdir1 gz:expressed_in='chassis'>{fdir}</fdir1></ode></friction></surface>"
        )
        links.append(_wheel_link(wheel, x, y, surface))
        joints.append(_joint(f"{wheel}_joint", "revolute", "chassis", wheel, "0 1 0"))
    plugin = f"""<plugin filename="gz-sim-mecanum-drive-system" name="gz::sim::systems::MecanumDrive">
      <front_left_joint>front_left_joint</front_left_joint><front_right_joint>front_right_joint</front_right_joint>
      <back_left_joint>rear_left_joint</back_left_joint><back_right_joint>rear_right_joint</back_right_joint>
      <wheel_separation>{TRACK_M}</wheel_separation><wheelbase>{WHEEL_BASE_M}</wheelbase>
      <wheel_radius>{WHEEL_RADIUS_M}</wheel_radius>{plugin_extra}
    </plugin>"""
    return f"<model name='{name}'>{''.join(links)}{''.join(joints)}{plugin}</model>"


TRACKS_SEPARATION_M = 0.45
TRACK_HEIGHT_M = 0.12
TRACK_LENGTH_M = 0.8  # from end cap to end cap, along the ground
# gz-sim's default, which suits these tracks (the parameter a user tunes to the vehicle)
STEERING_EFFICIENCY = 0.5


def tracked_robot(
    name: str = "tank",
    *,
    track_length_m: float = TRACK_LENGTH_M,
    efficiency: float = STEERING_EFFICIENCY,
    vehicle_extra: str = "",
) -> str:
    """A body on two tracks fixed to it, each a belt box between two round end caps, with a TrackController each
    (limited to 1 m/s) and a TrackedVehicle over both, laid out as gz-sim's tracked examples lay theirs out."""
    r = TRACK_HEIGHT_M / 2
    half = track_length_m / 2
    links = [
        f"<link name='chassis'><pose>0 0 {TRACK_HEIGHT_M + 0.04} 0 0 0</pose>{_inertial(12.0, 0.4)}"
        "<collision name='hull'><geometry><box><size>0.9 0.3 0.1</size></box></geometry></collision>"
        "<visual name='hull'><geometry><box><size>0.9 0.3 0.1</size></box></geometry></visual></link>"
    ]
    joints, plugins = [], []
    for side, y in (("left", TRACKS_SEPARATION_M / 2), ("right", -TRACKS_SEPARATION_M / 2)):
        caps = "".join(
            f"<collision name='cap{i}'><pose>{x} 0 0 1.5707963 0 0</pose><geometry><cylinder><radius>{r}</radius>"
            "<length>0.1</length></cylinder></geometry></collision>"
            for i, x in enumerate((-half, half))
        )
        links.append(
            f"<link name='{side}_track'><pose>0 {y} {r} 0 0 0</pose>{_inertial(2.0, 0.05)}"
            f"<collision name='run'><geometry><box><size>{track_length_m} 0.1 {TRACK_HEIGHT_M}</size></box>"
            f"</geometry></collision>{caps}</link>"
        )
        joints.append(
            f"<joint name='{side}_mount' type='fixed'><parent>chassis</parent><child>{side}_track</child></joint>"
        )
        plugins.append(
            '<plugin filename="gz-sim-track-controller-system" name="gz::sim::systems::TrackController">'
            f"<link>{side}_track</link><min_velocity>-1.0</min_velocity><max_velocity>1.0</max_velocity></plugin>"
        )
    plugins.append(
        '<plugin filename="gz-sim-tracked-vehicle-system" name="gz::sim::systems::TrackedVehicle">'
        "<left_track><link>left_track</link></left_track><right_track><link>right_track</link></right_track>"
        f"<tracks_separation>{TRACKS_SEPARATION_M}</tracks_separation><track_height>{TRACK_HEIGHT_M}</track_height>"
        f"<steering_efficiency>{efficiency}</steering_efficiency>{vehicle_extra}</plugin>"
    )
    return f"<model name='{name}'>{''.join(links)}{''.join(joints)}{''.join(plugins)}</model>"
