file(REMOVE_RECURSE
  "libelan_broadphase.a"
)
