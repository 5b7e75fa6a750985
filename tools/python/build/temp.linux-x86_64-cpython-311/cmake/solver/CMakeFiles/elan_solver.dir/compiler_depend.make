# Empty compiler generated dependencies file for elan_solver.
# This may be replaced when dependencies are built.
