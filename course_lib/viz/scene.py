"""Build meshcat commands from a MuJoCo model's own geoms (no hand-made second copy).

Every body becomes a meshcat path `/meshcat/mujoco/<body>`, every geom a child of it with its
fixed local transform; moving the robot means one `set_transform` per moving body. Object ids
are derived from the paths, so the same model always gives the same bytes.
"""

from __future__ import annotations

import uuid
from typing import Any

import meshcat.geometry as g
import mujoco
import numpy as np
from meshcat.commands import SetObject, SetProperty, SetTransform
from meshcat.path import Path

from .quaternions import pose_matrix

__all__ = [
    "ROOT",
    "body_paths",
    "body_transform",
    "camera_commands",
    "moving_bodies",
    "scene_commands",
]

ROOT = ("meshcat", "mujoco")
_IDS = uuid.UUID("6a0f3b52-3f7e-4c1e-9a55-7475727462ff")  # namespace of the course's scene ids
_Y_TO_Z = np.array([[1, 0, 0, 0], [0, 0, -1, 0], [0, 1, 0, 0], [0, 0, 0, 1]], dtype=float)
_FLOOR_HALF_M = 5.0


def _name(model: mujoco.MjModel, kind: mujoco.mjtObj, index: int, prefix: str) -> str:
    return mujoco.mj_id2name(model, kind, index) or f"{prefix}_{index}"


def body_paths(model: mujoco.MjModel) -> list[Path]:
    """Return the meshcat path of every body, indexed by body id."""
    kind = mujoco.mjtObj.mjOBJ_BODY
    return [Path((*ROOT, _name(model, kind, b, "body"))) for b in range(model.nbody)]


def moving_bodies(model: mujoco.MjModel) -> list[int]:
    """Return the ids of bodies that can move (not welded to the world)."""
    return [b for b in range(1, model.nbody) if model.body_weldid[b] != 0]


def body_transform(data: mujoco.MjData, body: int) -> np.ndarray:
    """Return the 4x4 world transform of `body` from the last forward/step."""
    matrix = np.eye(4)
    matrix[:3, :3] = data.xmat[body].reshape(3, 3)
    matrix[:3, 3] = data.xpos[body]
    return matrix


def _geometry(model: mujoco.MjModel, geom: int) -> tuple[Any, np.ndarray] | None:
    """Return the meshcat geometry of a geom and its intrinsic transform, or None."""
    kind, size = int(model.geom_type[geom]), model.geom_size[geom]
    types = mujoco.mjtGeom
    if kind == types.mjGEOM_BOX:
        return g.Box(list(2.0 * size)), np.eye(4)
    if kind == types.mjGEOM_SPHERE:
        return g.Sphere(float(size[0])), np.eye(4)
    if kind == types.mjGEOM_ELLIPSOID:
        return g.Ellipsoid(list(size)), np.eye(4)
    if kind in (types.mjGEOM_CYLINDER, types.mjGEOM_CAPSULE):
        height = 2.0 * size[1] + (2.0 * size[0] if kind == types.mjGEOM_CAPSULE else 0.0)
        return g.Cylinder(float(height), float(size[0])), _Y_TO_Z
    if kind == types.mjGEOM_PLANE:
        half = [s if s > 0 else _FLOOR_HALF_M for s in size[:2]]
        lowered = np.eye(4)
        lowered[2, 3] = -0.001  # just under meshcat's grid, which sits at z = 0
        return g.Box([2 * half[0], 2 * half[1], 0.002]), lowered
    if kind == types.mjGEOM_MESH:
        mesh = model.geom_dataid[geom]
        start, count = model.mesh_vertadr[mesh], model.mesh_vertnum[mesh]
        faces_at, nfaces = model.mesh_faceadr[mesh], model.mesh_facenum[mesh]
        vertices = model.mesh_vert[start : start + count]
        faces = model.mesh_face[faces_at : faces_at + nfaces]
        return g.TriangularMeshGeometry(vertices, faces), np.eye(4)
    return None


def _color(model: mujoco.MjModel, geom: int) -> tuple[int, float]:
    material = model.geom_matid[geom]
    rgba = model.mat_rgba[material] if material >= 0 else model.geom_rgba[geom]
    red, green, blue = (round(float(c) * 255) for c in rgba[:3])
    return (red << 16) | (green << 8) | blue, float(rgba[3])


def _fix_id(element: Any, key: str) -> None:
    element.uuid = str(uuid.uuid5(_IDS, key))


def scene_commands(model: mujoco.MjModel, data: mujoco.MjData) -> list[Any]:
    """Return the meshcat commands that draw every geom and place every body."""
    paths = body_paths(model)
    commands: list[Any] = []
    for geom in range(model.ngeom):
        if model.geom_rgba[geom][3] == 0 or model.geom_group[geom] > 2:
            continue
        built = _geometry(model, geom)
        if built is None:
            continue
        geometry, intrinsic = built
        name = _name(model, mujoco.mjtObj.mjOBJ_GEOM, geom, "geom")
        path = paths[model.geom_bodyid[geom]].append(name)
        color, opacity = _color(model, geom)
        material = g.MeshLambertMaterial(color=color, opacity=opacity)
        key = "/".join(path.lower().split("/"))
        _fix_id(geometry, key + "#geometry")
        _fix_id(material, key + "#material")
        command = SetObject(geometry, material, path)
        _fix_id(command.object, key + "#object")
        commands.append(command)
        local = pose_matrix(model.geom_pos[geom], model.geom_quat[geom]) @ intrinsic
        commands.append(SetTransform(local, path))
    for body in range(1, model.nbody):
        commands.append(SetTransform(body_transform(data, body), paths[body]))
    return commands


def camera_commands(position_m: tuple[float, float, float] = (-0.7, -1.0, 0.6)) -> list[Any]:
    """Return commands that place meshcat's camera at a world position, looking at the origin."""
    x, y, z = position_m
    camera = Path(("Cameras", "default", "rotated", "<object>"))
    return [SetProperty("position", [x, z, -y], camera)]  # three.js's camera frame is y-up
