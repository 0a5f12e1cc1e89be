# SPDX-License-Identifier: GPL-3.0-or-later
"""File > Import > Animated mesh (.ams): a mesh object with the file's first frame and
connectivity, played by a Mesh Cache modifier over the decoded frames. The frames are decoded
once into a PC2 point cache beside the .ams (NAME.ams.pc2, or NAME.ams.FIRST-LAST.pc2 for a
range), which Blender streams frame by
frame: of the ways measured (docs/blender.md: Mesh Cache, shape keys, a frame-change handler
over the decoder), it plays fastest forwards and backwards and keeps the .blend small."""
import os
import struct

import bpy
import numpy as np
from bpy_extras.io_utils import ImportHelper

from . import module

PC2_HEADER = struct.Struct('<12siiffi')
# The most a decoded cache may take on disk unless the user raises it: a small .ams can describe
# a huge mesh over many frames.
DEFAULT_CACHE_LIMIT_MB = 16384


class ImportAms(bpy.types.Operator, ImportHelper):
    """Import a compressed animated mesh (.ams): an object whose mesh plays its frames"""
    bl_idname = "import_anim.ams"
    bl_label = "Import Animated Mesh"
    bl_options = {'REGISTER', 'UNDO'}

    filename_ext = ".ams"
    filter_glob: bpy.props.StringProperty(default="*.ams", options={'HIDDEN'})
    first_frame: bpy.props.IntProperty(
        name="First frame", description="First frame of the file to import (0 = its first)", default=0, min=0)
    last_frame: bpy.props.IntProperty(
        name="Last frame", description="Last frame of the file to import (-1 = its last)", default=-1, min=-1)
    start_frame: bpy.props.IntProperty(
        name="Start at scene frame", description="Scene frame that shows the first imported frame", default=1)
    set_scene: bpy.props.BoolProperty(
        name="Set scene rate and range",
        description="Set the scene's frame rate to the file's and its frame range to the imported frames",
        default=True)
    cache_limit_mb: bpy.props.IntProperty(
        name="Cache limit (MB)", description="Refuse an import whose decoded cache would be larger",
        default=DEFAULT_CACHE_LIMIT_MB, min=1)

    def execute(self, context):
        try:
            ac = module.load(context)
            obj = import_animation(context, ac, self.filepath, self.first_frame, self.last_frame,
                                   self.start_frame, self.set_scene, self.cache_limit_mb)
        except module.ModuleMissing as missing:
            self.report({'ERROR'}, str(missing))
            return {'CANCELLED'}
        except (OSError, ValueError, IndexError, MemoryError) as error:
            self.report({'ERROR'}, f"{self.filepath}: {error}")
            return {'CANCELLED'}
        except Exception as error:  # animcompress.Error, whose class lives in the module
            self.report({'ERROR'}, str(error))
            return {'CANCELLED'}
        self.report({'INFO'}, f"{obj.name}: {obj['ams_frames']} frames of {len(obj.data.vertices)} vertices")
        return {'FINISHED'}


def frame_range(frames, first, last):
    """(first, end) of the frames to import, end excluded; ValueError when outside the file."""
    end = frames if last < 0 else last + 1
    if not 0 <= first < end <= frames:
        asked = f"{first} to {'the last' if last < 0 else last}"
        raise ValueError(f"frames {asked} are not in the file, whose frames are 0 to {frames - 1}")
    return first, end


def cache_path(path, first, end, frames):
    """NAME.ams.pc2 for all frames, NAME.ams.FIRST-LAST.pc2 for a range: an import of another
    range of the same file must not replace the cache an earlier import plays."""
    return f"{path}.pc2" if (first, end) == (0, frames) else f"{path}.{first}-{end - 1}.pc2"


def new_mesh(name, positions, faces):
    mesh = bpy.data.meshes.new(name)
    mesh.vertices.add(len(positions))
    mesh.vertices.foreach_set('co', positions.ravel())
    mesh.loops.add(3 * len(faces))
    mesh.loops.foreach_set('vertex_index', faces.astype(np.int32).ravel())
    mesh.polygons.add(len(faces))
    mesh.polygons.foreach_set('loop_start', np.arange(0, 3 * len(faces), 3, dtype=np.int32))
    if bpy.app.version < (4, 0, 0):  # from 4.0 on a polygon's size follows from the starts
        mesh.polygons.foreach_set('loop_total', np.full(len(faces), 3, dtype=np.int32))
    mesh.update()
    mesh.validate()  # degenerate triangles would make an invalid Blender mesh
    return mesh


def write_cache(context, decoder, path, first, end):
    """Frames first..end-1 as a PC2 at path, written to a temporary beside it, then renamed."""
    vertices = decoder.info()['vertices']
    temporary = f"{path}.{os.getpid()}.tmp"
    wm = context.window_manager
    wm.progress_begin(first, end)
    try:
        with open(temporary, 'wb') as f:
            f.write(PC2_HEADER.pack(b'POINTCACHE2\0', 1, vertices, 0.0, 1.0, end - first))
            for k in range(first, end):
                f.write(np.ascontiguousarray(decoder[k], dtype='<f4').tobytes())
                wm.progress_update(k)
        os.replace(temporary, path)
    finally:
        wm.progress_end()
        if os.path.exists(temporary):
            os.remove(temporary)


def import_animation(context, ac, path, first, last, start_frame, set_scene, cache_limit_mb):
    decoder = ac.open(path)
    info = decoder.info()
    first, end = frame_range(info['frames'], first, last)
    cache_bytes = PC2_HEADER.size + 12 * info['vertices'] * (end - first)
    if cache_bytes > cache_limit_mb * 2**20:
        raise ValueError(f"the decoded frames would take {cache_bytes / 2**20:.0f} MB, above the cache "
                         f"limit of {cache_limit_mb} MB: import fewer frames or raise the limit")
    cache = cache_path(bpy.path.abspath(path), first, end, info['frames'])
    write_cache(context, decoder, cache, first, end)
    name = os.path.splitext(os.path.basename(path))[0]
    obj = bpy.data.objects.new(name, new_mesh(name, decoder[first], decoder.faces))
    context.collection.objects.link(obj)
    modifier = obj.modifiers.new("Animated mesh (.ams)", 'MESH_CACHE')
    modifier.cache_format = 'PC2'
    modifier.filepath = cache
    modifier.frame_start = start_frame
    modifier.interpolation = 'NONE'  # a frame shows as decoded, never a blend of two
    obj['ams_file'], obj['ams_first_frame'], obj['ams_frames'] = path, first, end - first
    if set_scene:
        rate = info['frame_rate']
        context.scene.render.fps = max(1, round(rate))
        context.scene.render.fps_base = context.scene.render.fps / rate
        context.scene.frame_start, context.scene.frame_end = start_frame, start_frame + end - first - 1
    for other in context.view_layer.objects:
        other.select_set(False)
    context.view_layer.objects.active = obj
    obj.select_set(True)
    return obj
