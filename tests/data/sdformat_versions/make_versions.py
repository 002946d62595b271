#!/usr/bin/env python3
"""Writes the four-bar of ../four_bar_loop.sdf stood up in the x-z plane (every pose
turned by +90 deg about x) in SDFormat 1.4, 1.5, 1.6 and 1.7, each giving its joint
axes the way its own version means them:
  1.7: in the joint frame (the child link's frame moved by the joint's <pose>);
  1.6 and 1.5: in the joint frame, or with <use_parent_model_frame>true in the model
       frame (crank and world_rocker here);
  1.4: always in the model frame.
The joint axes are +z of the links, which the turn makes -y of the model, so a reader
that took a 1.4 axis in the joint frame would get +z of the world instead: another
mechanism. Run: python3 make_versions.py (writes four_bar_tilted_1.*.sdf beside it)."""
import math
import pathlib

HERE = pathlib.Path(__file__).resolve().parent
# The untilted four-bar (../four_bar_loop.sdf): link poses (x, y, yaw) in the x-y plane.
LINKS = [("driver", (-2.0, 0.0), 1.5707963267948966, 1.0),
         ("coupler", (-2.0, 1.0), 0.18127970853157052, 4.8),
         ("rocker", (2.0, 0.0), 1.2018068856832935, 2.0)]
JOINTS = [("crank", "world", "driver", None),
          ("world_rocker", "world", "rocker", None),
          ("driver_coupler", "driver", "coupler", None),
          ("coupler_rocker", "coupler", "rocker", "2 0 0 0 0 0")]


def tilted_pose(xy, yaw):
    """The pose turned by +90 deg about x: position R_x p, rotation R_x R_z(yaw) as
    SDFormat's roll pitch yaw (R = R_z(yaw') R_y(pitch') R_x(roll'))."""
    x, y = xy
    c, s = math.cos(yaw), math.sin(yaw)
    # R_x(90) = [[1,0,0],[0,0,-1],[0,1,0]]; R_z(yaw) = [[c,-s,0],[s,c,0],[0,0,1]].
    r = [[c, -s, 0.0], [0.0, 0.0, -1.0], [s, c, 0.0]]
    pitch = -math.asin(r[2][0])
    roll = math.atan2(r[2][1], r[2][2])
    yaw2 = math.atan2(r[1][0], r[0][0])
    return (x, 0.0, y), (roll, pitch, yaw2)


def number(v):
    return "0" if v == 0 else repr(float(v))


def link_xml(name, xy, yaw, length):
    p, rpy = tilted_pose(xy, yaw)
    pose = " ".join(number(v) for v in p + rpy)
    return f"""    <link name="{name}">
      <pose>{pose}</pose>
      <inertial>
        <pose>{number(length / 2)} 0 0 0 0 0</pose>
        <mass>1</mass>
        <inertia><ixx>0.001</ixx><iyy>0.1</iyy><izz>0.1</izz><ixy>0</ixy><ixz>0</ixz><iyz>0</iyz></inertia>
      </inertial>
    </link>
"""


def axis_xml(version, joint):
    """The axis +z of the child link: (0, 0, 1) in the joint frame, (0, -1, 0) in the model frame."""
    model_frame = version == "1.4" or (version in ("1.5", "1.6") and joint in ("crank", "world_rocker"))
    if not model_frame:
        return "<axis><xyz>0 0 1</xyz></axis>"
    if version == "1.4":
        return "<axis><xyz>0 -1 0</xyz></axis>"
    return "<axis><xyz>0 -1 0</xyz><use_parent_model_frame>true</use_parent_model_frame></axis>"


def write(version):
    text = [f'<?xml version="1.0"?>\n<!-- Written by make_versions.py: the four-bar of four_bar_loop.sdf '
            f'stood up in the x-z plane, SDFormat {version}. -->\n<sdf version="{version}">\n'
            f'  <model name="four_bar_tilted">\n']
    for name, xy, yaw, length in LINKS:
        text.append(link_xml(name, xy, yaw, length))
    for name, parent, child, pose in JOINTS:
        pose_xml = f"\n      <pose>{pose}</pose>" if pose else ""
        text.append(f"""    <joint name="{name}" type="revolute">{pose_xml}
      <parent>{parent}</parent>
      <child>{child}</child>
      {axis_xml(version, name)}
    </joint>
""")
    text.append("  </model>\n</sdf>\n")
    (HERE / f"four_bar_tilted_{version}.sdf").write_text("".join(text))


for v in ("1.4", "1.5", "1.6", "1.7"):
    write(v)
