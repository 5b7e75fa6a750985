# Empty dependencies file for elan_scene.
# This may be replaced when dependencies are built.
