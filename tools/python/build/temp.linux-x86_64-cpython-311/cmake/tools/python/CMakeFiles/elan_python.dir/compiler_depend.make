# Empty compiler generated dependencies file for elan_python.
# This may be replaced when dependencies are built.
