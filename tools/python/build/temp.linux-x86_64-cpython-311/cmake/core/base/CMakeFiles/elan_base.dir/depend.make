# Empty dependencies file for elan_base.
# This may be replaced when dependencies are built.
