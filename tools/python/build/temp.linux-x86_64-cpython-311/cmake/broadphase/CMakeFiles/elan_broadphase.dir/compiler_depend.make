# Empty compiler generated dependencies file for elan_broadphase.
# This may be replaced when dependencies are built.
