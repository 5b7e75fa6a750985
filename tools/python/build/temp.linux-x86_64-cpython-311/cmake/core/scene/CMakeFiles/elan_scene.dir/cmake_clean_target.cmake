file(REMOVE_RECURSE
  "libelan_scene.a"
)
