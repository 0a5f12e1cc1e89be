# SPDX-License-Identifier: GPL-3.0-or-later
"""Finding the animcompress Python module: where Blender's Python finds it, or in the folder the
add-on's preferences name (Blender 4.x from blender.org ignores PYTHONPATH)."""
import importlib
import sys


class ModuleMissing(Exception):
    pass


def _preferences(context):
    addon = context.preferences.addons.get(__package__)
    return addon.preferences if addon else None


def load(context):
    """The animcompress module; ModuleMissing with what to do when it cannot be imported."""
    prefs = _preferences(context)
    folder = bpy_path_abs(prefs.module_folder) if prefs and prefs.module_folder else ''
    if folder and folder not in sys.path:
        sys.path.append(folder)
    try:
        return importlib.import_module('animcompress')
    except ImportError as error:
        raise ModuleMissing(
            f"the animcompress Python module cannot be imported ({error}); build it (README: "
            "'Use it as a library') and name its folder in Edit > Preferences > Add-ons > "
            "Animated mesh (.ams)") from error


def status(context):
    try:
        return f"animcompress {load(context).__version__} found"
    except ModuleMissing as missing:
        return str(missing)[:120]


def bpy_path_abs(path):
    import bpy
    return bpy.path.abspath(path)
