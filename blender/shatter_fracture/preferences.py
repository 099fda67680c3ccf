"""The add-on's preferences: where the shatter binary is."""

import bpy
from bpy.props import StringProperty

from . import runner


class ShatterFracturePreferences(bpy.types.AddonPreferences):
    bl_idname = __package__

    shatter_path: StringProperty(
        name="shatter binary",
        description="Path of the shatter executable (or of the folder holding it); "
                    "empty: look for `shatter` on PATH",
        subtype='FILE_PATH',
        default="",
    )

    def draw(self, context):
        layout = self.layout
        layout.prop(self, "shatter_path")
        try:
            found = runner.find_binary(self.shatter_path)
            layout.label(text="Using " + found, icon='CHECKMARK')
        except runner.ShatterError as e:
            layout.label(text=str(e), icon='ERROR')


def preferences(context):
    """This add-on's preferences (None when it is not registered as an add-on)."""
    addon = context.preferences.addons.get(__package__)
    return addon.preferences if addon is not None else None
