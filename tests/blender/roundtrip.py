# SPDX-License-Identifier: GPL-3.0-or-later
# Run inside Blender by blender_test.sh: enables the io_anim_ams add-on as a user would, makes an
# armature-driven mesh that also moves, exports it with bpy.ops.export_anim.ams, imports the file
# with bpy.ops.import_anim.ams, and checks that the imported object plays the original's
# evaluated frames within the codec's bound; then that bad files end as an error report.
#   usage: blender -b --factory-startup --python-exit-code 1 --python roundtrip.py -- OUT_DIR
import math
import os
import shutil
import sys

import addon_utils
import bpy
import numpy as np

OUT = sys.argv[sys.argv.index('--') + 1]
RINGS, SIDES, FRAMES = 24, 16, 40
failures = []


def check(condition, message):
    print(('ok: ' if condition else 'FAIL: ') + message)
    if not condition:
        failures.append(message)


def column():
    """A closed tube of quads, 4 units tall, bent by a two-bone armature and moving sideways."""
    verts = [(math.cos(2 * math.pi * s / SIDES), math.sin(2 * math.pi * s / SIDES), 4 * r / (RINGS - 1))
             for r in range(RINGS) for s in range(SIDES)]
    quads = [(r * SIDES + s, r * SIDES + (s + 1) % SIDES, (r + 1) * SIDES + (s + 1) % SIDES, (r + 1) * SIDES + s)
             for r in range(RINGS - 1) for s in range(SIDES)]
    caps = [tuple(range(SIDES))[::-1], tuple(range((RINGS - 1) * SIDES, RINGS * SIDES))]
    mesh = bpy.data.meshes.new('column')
    mesh.from_pydata(verts, [], quads + caps)
    obj = bpy.data.objects.new('column', mesh)
    bpy.context.collection.objects.link(obj)
    arm_data = bpy.data.armatures.new('rig')
    rig = bpy.data.objects.new('rig', arm_data)
    bpy.context.collection.objects.link(rig)
    bpy.context.view_layer.objects.active = rig
    bpy.ops.object.mode_set(mode='EDIT')
    lower = arm_data.edit_bones.new('lower')
    lower.head, lower.tail = (0, 0, 0), (0, 0, 2)
    upper = arm_data.edit_bones.new('upper')
    upper.head, upper.tail, upper.parent = (0, 0, 2), (0, 0, 4), lower
    bpy.ops.object.mode_set(mode='OBJECT')
    for name in ('lower', 'upper'):
        group = obj.vertex_groups.new(name=name)
        for i, v in enumerate(verts):
            w = min(max((v[2] - 1.5) / 1.0, 0.0), 1.0)
            group.add([i], w if name == 'upper' else 1 - w, 'REPLACE')
    modifier = obj.modifiers.new('rig', 'ARMATURE')
    modifier.object = rig
    bone = rig.pose.bones['upper']
    bone.rotation_mode = 'XYZ'
    for frame, angle in ((1, 0.0), (20, 1.1), (FRAMES, -0.6)):
        bone.rotation_euler = (angle, 0.0, 0.3 * angle)
        bone.keyframe_insert('rotation_euler', frame=frame)
        obj.location = (0.05 * frame, 0.0, 0.0)
        obj.keyframe_insert('location', frame=frame)
    return obj


def evaluated(obj):
    """World positions of obj's evaluated mesh at the current frame."""
    ev = obj.evaluated_get(bpy.context.evaluated_depsgraph_get())
    mesh = ev.to_mesh()
    co = np.empty(3 * len(mesh.vertices), dtype=np.float32)
    mesh.vertices.foreach_get('co', co)
    m = np.array(ev.matrix_world)
    ev.to_mesh_clear()
    return (co.reshape(-1, 3) @ m[:3, :3].T + m[:3, 3]).astype(np.float32)


def played(obj, frames):
    out = []
    for f in frames:
        bpy.context.scene.frame_set(f)
        out.append(evaluated(obj))
    return np.stack(out)


def operator_error(operator, **kwargs):
    """The message of the error report an operator call ends with, or None when it succeeds."""
    try:
        result = operator(**kwargs)
    except RuntimeError as error:
        return str(error)
    return None if result == {'FINISHED'} else f'result {result}'


def main():
    os.makedirs(OUT, exist_ok=True)
    enabled = addon_utils.enable('io_anim_ams', default_set=True)
    check(enabled is not None, 'the io_anim_ams add-on is enabled from the user add-on folder')
    import animcompress as ac
    scene = bpy.context.scene
    scene.frame_start, scene.frame_end = 1, FRAMES
    scene.render.fps, scene.render.fps_base = 24, 1.0
    obj = column()
    original = played(obj, range(1, FRAMES + 1))
    check(float(np.abs(original[20] - original[0]).max()) > 0.5, 'the armature moves the mesh')

    for settings in ({'max_error': 1.0}, {'codec': 'trajectory', 'rate_mode': 'TARGET_KG', 'target_kg': 0.3},
                     {'codec': 'trajectory2', 'rate_mode': 'TARGET_KG', 'target_kg': 0.3}):
        for other in bpy.context.view_layer.objects:
            other.select_set(False)
        bpy.context.view_layer.objects.active = obj
        ams = os.path.join(OUT, 'column_%s.ams' % settings.get('codec', 'auto'))
        error = operator_error(bpy.ops.export_anim.ams, filepath=ams, **settings)
        check(error is None and os.path.getsize(ams) > 0, f'export {settings}: {error or "written"}')
        info = ac.info(ams)
        check(info['frames'] == FRAMES and info['vertices'] == RINGS * SIDES, f'{ams}: {info["frames"]} frames')
        check(abs(info['frame_rate'] - 24) < 1e-9, f'{ams}: frame rate {info["frame_rate"]}')
        error = operator_error(bpy.ops.import_anim.ams, filepath=ams, start_frame=1)
        check(error is None, f'import {ams}: {error or "imported"}')
        imported = bpy.context.active_object
        check(imported is not obj and imported.modifiers[0].type == 'MESH_CACHE', 'a new object with a Mesh Cache')
        check(os.path.exists(ams + '.pc2'), 'the decoded cache lies beside the file')
        back = played(imported, range(1, FRAMES + 1))
        figures = ac.compare(original, back)
        if 'max_error' in settings:
            check(figures['max_error_rel_cube'] <= 0.01 * 1.02,
                  f"max error {figures['max_error_rel_cube']:.5f} of the cube within 1 %")
        else:
            check(figures['kg_error'] <= 0.3 * 1.02, f"KG error {figures['kg_error']:.4f} % within 0.3 %")
        check(figures['kg_error'] > 0, 'the frames went through the codec (not a copy)')
        check(np.array_equal(back[5], ac.open(ams)[5]), 'frame 5 plays exactly as decoded')
        bpy.data.objects.remove(imported)
        check(scene.frame_start == 1 and scene.frame_end == FRAMES, 'the scene range is the imported frames')

    # Part of a file, at another scene frame.
    ams = os.path.join(OUT, 'column_auto.ams')
    check(operator_error(bpy.ops.import_anim.ams, filepath=ams, first_frame=10, last_frame=19, start_frame=101)
          is None, 'import frames 10 to 19 at scene frame 101')
    part = bpy.context.active_object
    bpy.context.scene.frame_set(105)
    check(np.array_equal(evaluated(part), ac.open(ams)[14]), 'scene frame 105 shows file frame 14')
    check(part.modifiers[0].filepath == ams + '.10-19.pc2', f'a range has its own cache: {part.modifiers[0].filepath}')
    check((scene.frame_start, scene.frame_end) == (101, 110), f'scene range {scene.frame_start}-{scene.frame_end}')

    # Bad files end as an error report, never a crash, and make no object.
    data = open(ams, 'rb').read()
    objects = len(bpy.data.objects)
    bad = {'truncated.ams': data[:len(data) // 2], 'garbage.ams': b'not an ams file' * 10, 'empty.ams': b'',
           'flipped.ams': data[:200] + bytes([data[200] ^ 0x40]) + data[201:]}
    for name, content in bad.items():
        path = os.path.join(OUT, name)
        with open(path, 'wb') as f:
            f.write(content)
        error = operator_error(bpy.ops.import_anim.ams, filepath=path)
        check(error is not None and error.startswith('Error'), f'{name}: {error}')
    error = operator_error(bpy.ops.import_anim.ams, filepath=os.path.join(OUT, 'missing.ams'))
    check(error is not None and 'missing.ams' in error, f'missing file: {error}')
    error = operator_error(bpy.ops.import_anim.ams, filepath=ams, first_frame=50)
    check(error is not None and 'not in the file' in error, f'frames outside the file: {error}')
    error = operator_error(bpy.ops.import_anim.ams, filepath=ams, cache_limit_mb=1, last_frame=39)
    check(error is None, 'a 40-frame cache fits in 1 MB')
    check(len(bpy.data.objects) == objects + 1, 'failed imports made no object')
    bpy.context.view_layer.objects.active = bpy.data.objects['rig']
    error = operator_error(bpy.ops.export_anim.ams, filepath=os.path.join(OUT, 'rig.ams'))
    check(error is not None and 'not a mesh' in error, f'export of an armature: {error}')
    check(not os.path.exists(os.path.join(OUT, 'rig.ams')), 'a failed export writes nothing')

    print(f'blender_test: {0 if failures else 1} passed, {len(failures)} failed')
    if failures:
        sys.exit(1)


main()
