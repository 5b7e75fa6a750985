# Empty dependencies file for elan_narrowphase.
# This may be replaced when dependencies are built.
