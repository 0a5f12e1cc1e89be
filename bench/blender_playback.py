# SPDX-License-Identifier: GPL-3.0-or-later
"""Run inside Blender by bench/bench_blender.py: one way of playing an .ams in Blender, timed.

  cache    the add-on's import (bpy.ops.import_anim.ams): a Mesh Cache modifier over the frames
           decoded once into a PC2 beside the file
  keys     one shape key per frame, each keyed to weight 1 at its own frame only
  handler  a frame-change handler that decodes the scene's frame into the mesh (the decoder's
           random access; a frame's group is decoded from its start when playing backwards)

Prints one line 'RESULT {json}': setup seconds, milliseconds per frame forwards and backwards
(every 7th frame, last first), the largest difference from the decoded frame 123 (or the last),
and the process's peak RSS in MB.
usage: blender -b --factory-startup --python blender_playback.py -- FILE.ams METHOD"""
import json
import resource
import sys
import time

import addon_utils
import bpy
import numpy as np

path, method = sys.argv[sys.argv.index('--') + 1:][:2]
addon_utils.enable('io_anim_ams', default_set=True)
import animcompress as ac  # noqa: E402
from io_anim_ams import import_ams  # noqa: E402

decoder = ac.open(path)
frames = len(decoder)
scene = bpy.context.scene
start = time.perf_counter()
if method == 'cache':
    bpy.ops.import_anim.ams(filepath=path, start_frame=0)
    obj = bpy.context.active_object
else:
    mesh = import_ams.new_mesh('played', decoder[0], decoder.faces)
    obj = bpy.data.objects.new('played', mesh)
    scene.collection.objects.link(obj)
    scene.frame_start, scene.frame_end = 0, frames - 1
    if method == 'keys':
        obj.shape_key_add(name='Basis', from_mix=False)
        for k in range(frames):
            key = obj.shape_key_add(name=f'frame_{k:05d}', from_mix=False)
            key.data.foreach_set('co', decoder[k].ravel())
            for frame, value in ((k - 1, 0.0), (k, 1.0), (k + 1, 0.0)):
                key.value = value
                key.keyframe_insert('value', frame=frame)
        for curve in mesh.shape_keys.animation_data.action.fcurves:
            for point in curve.keyframe_points:
                point.interpolation = 'CONSTANT'
    else:
        shown = {'frame': None}

        def show_frame(scene, depsgraph=None):
            k = min(max(scene.frame_current, 0), frames - 1)
            if shown['frame'] != k:
                mesh.vertices.foreach_set('co', decoder[k].ravel())
                mesh.update()
                shown['frame'] = k
        bpy.app.handlers.frame_change_pre.append(show_frame)
setup = time.perf_counter() - start


def positions():
    evaluated = obj.evaluated_get(bpy.context.evaluated_depsgraph_get())
    co = np.empty(3 * len(evaluated.data.vertices), dtype=np.float32)
    evaluated.data.vertices.foreach_get('co', co)
    return co


def play(order):
    begin = time.perf_counter()
    for k in order:
        scene.frame_set(k)
        positions()
    return 1000 * (time.perf_counter() - begin) / len(order)


forwards = play(range(frames))
backwards = play(range(frames - 1, -1, -7))
probe = min(123, frames - 1)
scene.frame_set(probe)
error = float(np.abs(positions() - decoder[probe].ravel()).max())
print('RESULT ' + json.dumps({'method': method, 'setup_s': setup, 'forwards_ms': forwards, 'backwards_ms': backwards,
                              'error': error, 'peak_rss_mb': resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024}))
