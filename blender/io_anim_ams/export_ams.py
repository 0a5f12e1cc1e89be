# SPDX-License-Identifier: GPL-3.0-or-later
"""File > Export > Animated mesh (.ams): the active object's evaluated mesh (modifiers, armatures,
shape keys and its own motion applied, in world coordinates) at every frame of the scene's
frame range, triangulated as Blender draws it, encoded by animcompress."""
import os

import bpy
import numpy as np
from bpy_extras.io_utils import ExportHelper

from . import module

CODECS = [('auto', "Auto", "Per frame group, the smaller of the trajectory2 codec and the other one (animc's default)"),
          ('trajectory', "Trajectory", "Principal components of the vertex trajectories"),
          ('affine-octree', "Affine-Octree", "Frame-to-frame affine motion of octree cells"),
          ('wavelet', "Wavelet", "Progressive wavelet coding (target KG only)"),
          ('trajectory2', "Trajectory 2", "Trajectory codec with a basis per part of the mesh: the smallest files")]


class ExportAms(bpy.types.Operator, ExportHelper):
    """Export the active object's evaluated frames over the scene's frame range as a compressed .ams"""
    bl_idname = "export_anim.ams"
    bl_label = "Export Animated Mesh"

    filename_ext = ".ams"
    filter_glob: bpy.props.StringProperty(default="*.ams", options={'HIDDEN'})
    codec: bpy.props.EnumProperty(name="Codec", items=CODECS, default='auto')
    rate_mode: bpy.props.EnumProperty(
        name="Bound", default='MAX_ERROR',
        items=[('MAX_ERROR', "Max error", "Every vertex within this fraction of the frame's bounding cube"),
               ('TARGET_KG', "Target KG error", "The Karni-Gotsman error of the whole sequence at most this")])
    max_error: bpy.props.FloatProperty(
        name="Max error (%)", description="Largest vertex error, in % of the side of the frame's bounding cube",
        default=1.0, min=0.001, max=50.0)
    target_kg: bpy.props.FloatProperty(
        name="Target KG (%)", description="Karni-Gotsman error the file may reach, in %", default=0.3, min=0.001,
        max=50.0)
    iframe_interval: bpy.props.IntProperty(
        name="Random access every", description="Frames between independently decodable groups (0 = one group)",
        default=0, min=0)

    def draw(self, context):
        layout = self.layout
        layout.prop(self, "codec")
        layout.prop(self, "rate_mode")
        layout.prop(self, "max_error" if self.rate_mode == 'MAX_ERROR' else "target_kg")
        layout.prop(self, "iframe_interval")

    def execute(self, context):
        obj = context.active_object
        if obj is None or obj.type != 'MESH':
            self.report({'ERROR'}, "select the mesh object to export (the active object is not a mesh)")
            return {'CANCELLED'}
        try:
            ac = module.load(context)
            frames, faces = evaluated_frames(context, obj)
            options = ({'max_error': self.max_error / 100} if self.rate_mode == 'MAX_ERROR'
                       else {'target_kg': self.target_kg})
            rate = context.scene.render.fps / context.scene.render.fps_base
            data = ac.encode(frames, faces, codec=self.codec, iframe_interval=self.iframe_interval,
                             frame_rate=rate, **options)
            write_atomically(self.filepath, data)
        except module.ModuleMissing as missing:
            self.report({'ERROR'}, str(missing))
            return {'CANCELLED'}
        except (OSError, ValueError, MemoryError) as error:
            self.report({'ERROR'}, f"{self.filepath}: {error}")
            return {'CANCELLED'}
        except Exception as error:  # animcompress.Error, whose class lives in the module
            self.report({'ERROR'}, str(error))
            return {'CANCELLED'}
        bpvf = 8 * len(data) / frames.shape[0] / frames.shape[1]
        self.report({'INFO'}, f"{self.filepath}: {frames.shape[0]} frames of {frames.shape[1]} vertices, "
                              f"{len(data)} bytes ({bpvf:.3f} bits/vertex/frame)")
        return {'FINISHED'}


def evaluated_mesh(context, obj):
    """(world positions (N, 3) float32, triangles (T, 3) uint32) of obj at the current frame."""
    evaluated = obj.evaluated_get(context.evaluated_depsgraph_get())
    mesh = evaluated.to_mesh()
    try:
        positions = np.empty(3 * len(mesh.vertices), dtype=np.float32)
        mesh.vertices.foreach_get('co', positions)
        mesh.calc_loop_triangles()
        triangles = np.empty(3 * len(mesh.loop_triangles), dtype=np.uint32)
        mesh.loop_triangles.foreach_get('vertices', triangles)
        world = np.array(evaluated.matrix_world, dtype=np.float64)
    finally:
        evaluated.to_mesh_clear()
    positions = positions.reshape(-1, 3) @ world[:3, :3].T + world[:3, 3]
    return positions.astype(np.float32), triangles.reshape(-1, 3)


def evaluated_frames(context, obj):
    """(frames (F, N, 3), triangles (T, 3)) over the scene's frame range; ValueError if the mesh's
    vertices or faces change on the way (a codec needs one connectivity)."""
    scene = context.scene
    frame_numbers = range(scene.frame_start, scene.frame_end + 1)
    kept = scene.frame_current
    wm = context.window_manager
    wm.progress_begin(0, len(frame_numbers))
    try:
        frames, faces = None, None
        for i, number in enumerate(frame_numbers):
            scene.frame_set(number)
            positions, triangles = evaluated_mesh(context, obj)
            if frames is None:
                frames = np.empty((len(frame_numbers),) + positions.shape, dtype=np.float32)
                faces = triangles
            elif positions.shape != frames.shape[1:] or not np.array_equal(triangles, faces):
                raise ValueError(f"frame {number}: the evaluated mesh of {obj.name} has other vertices or "
                                 f"faces than at frame {scene.frame_start}")
            frames[i] = positions
            wm.progress_update(i)
    finally:
        wm.progress_end()
        scene.frame_set(kept)
    if len(faces) == 0:
        raise ValueError(f"{obj.name} has no faces")
    return frames, faces


def write_atomically(path, data):
    temporary = f"{path}.{os.getpid()}.tmp"
    try:
        with open(temporary, 'wb') as f:
            f.write(data)
        os.replace(temporary, path)
    finally:
        if os.path.exists(temporary):
            os.remove(temporary)
