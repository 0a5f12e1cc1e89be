# SPDX-License-Identifier: GPL-3.0-or-later
"""Import and export animated meshes as .ams files (animcompress): File > Import > Animated mesh
(.ams) makes an object whose mesh plays the file's frames; File > Export > Animated mesh (.ams)
writes the evaluated frames of the active object over the scene's frame range."""

bl_info = {
    "name": "Animated mesh (.ams)",
    "author": "animcompress",
    "version": (1, 1, 0),
    "blender": (3, 4, 0),
    "location": "File > Import / Export > Animated mesh (.ams)",
    "description": "Compressed animated triangle meshes (animcompress .ams files)",
    "category": "Import-Export",
}

import bpy  # noqa: E402

from . import export_ams, import_ams, module  # noqa: E402


class AmsPreferences(bpy.types.AddonPreferences):
    bl_idname = __package__

    module_folder: bpy.props.StringProperty(
        name="animcompress module folder",
        description="Folder holding the animcompress Python module (animcompress.cpython-311-*.so), "
                    "when Blender's Python does not find it by itself",
        subtype='DIR_PATH')

    def draw(self, context):
        self.layout.prop(self, "module_folder")
        self.layout.label(text=module.status(context))


def menu_import(self, context):
    self.layout.operator(import_ams.ImportAms.bl_idname, text="Animated mesh (.ams)")


def menu_export(self, context):
    self.layout.operator(export_ams.ExportAms.bl_idname, text="Animated mesh (.ams)")


CLASSES = (AmsPreferences, import_ams.ImportAms, export_ams.ExportAms)


def register():
    for cls in CLASSES:
        bpy.utils.register_class(cls)
    bpy.types.TOPBAR_MT_file_import.append(menu_import)
    bpy.types.TOPBAR_MT_file_export.append(menu_export)


def unregister():
    bpy.types.TOPBAR_MT_file_export.remove(menu_export)
    bpy.types.TOPBAR_MT_file_import.remove(menu_import)
    for cls in reversed(CLASSES):
        bpy.utils.unregister_class(cls)
