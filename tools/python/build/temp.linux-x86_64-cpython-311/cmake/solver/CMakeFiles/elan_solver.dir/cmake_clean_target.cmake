file(REMOVE_RECURSE
  "libelan_solver.a"
)
