# Debian's paraview-dev ships neither the wrap hierarchies of ParaView's VTK and ParaView modules
# (lib/<arch>/vtk/hierarchy/ParaView/*-hierarchy.txt) nor anything that makes them, yet the
# client-server wrapping of a plugin's modules reads those of every module it depends on. They
# list each wrapped class and its superclass, and are made here as ParaView's own build makes them:
# vtkWrapHierarchy over each module's installed headers, dependencies first.
#
# cloudvis_paraview_wrap_hierarchies(TARGET <name> MODULES <module>...): a target that writes the
# hierarchy of each module in MODULES and of every module they depend on, where the module's
# target says it lies (in the private prefix, paraview/make-prefix.sh), unless it is there already.

function(_cloudvis_hierarchy_closure module)
  if(NOT TARGET "${module}" OR "${module}" IN_LIST _cloudvis_hierarchy_seen)
    return()
  endif()
  list(APPEND _cloudvis_hierarchy_seen "${module}")
  set(_cloudvis_hierarchy_seen "${_cloudvis_hierarchy_seen}" PARENT_SCOPE)
  get_property(depends TARGET "${module}" PROPERTY INTERFACE_vtk_module_depends)
  foreach(dependency IN LISTS depends)
    _cloudvis_hierarchy_closure("${dependency}")
    set(_cloudvis_hierarchy_seen "${_cloudvis_hierarchy_seen}" PARENT_SCOPE)
  endforeach()
endfunction()

function(cloudvis_paraview_wrap_hierarchies)
  cmake_parse_arguments(PARSE_ARGV 0 H "" "TARGET" "MODULES")
  set(_cloudvis_hierarchy_seen)
  foreach(module IN LISTS H_MODULES)
    _cloudvis_hierarchy_closure("${module}")
  endforeach()

  set(outputs)
  foreach(module IN LISTS _cloudvis_hierarchy_seen)
    get_property(hierarchy TARGET "${module}" PROPERTY INTERFACE_vtk_module_hierarchy)
    get_property(exclude TARGET "${module}" PROPERTY INTERFACE_vtk_module_exclude_wrap)
    get_property(headers TARGET "${module}" PROPERTY INTERFACE_vtk_module_headers)
    get_property(library TARGET "${module}" PROPERTY INTERFACE_vtk_module_library_name)
    if(NOT hierarchy OR exclude OR NOT headers)
      continue()
    endif()
    # Its dependencies' hierarchies, written before it.
    set(depends_files)
    get_property(depends TARGET "${module}" PROPERTY INTERFACE_vtk_module_depends)
    foreach(dependency IN LISTS depends)
      if(TARGET "${dependency}")
        get_property(dependency_hierarchy TARGET "${dependency}"
          PROPERTY INTERFACE_vtk_module_hierarchy)
        get_property(dependency_exclude TARGET "${dependency}"
          PROPERTY INTERFACE_vtk_module_exclude_wrap)
        if(dependency_hierarchy AND NOT dependency_exclude)
          list(APPEND depends_files "${dependency_hierarchy}")
        endif()
      endif()
    endforeach()
    set(work "${CMAKE_BINARY_DIR}/wrap-hierarchies/${library}")
    set(data "")
    foreach(header IN LISTS headers)
      string(APPEND data "${header};${library}\n")
    endforeach()
    file(WRITE "${work}.data" "${data}")
    set(depends_args "")
    foreach(file IN LISTS depends_files)
      string(APPEND depends_args "\"${file}\"\n")
    endforeach()
    file(WRITE "${work}.depends.args" "${depends_args}")
    get_property(includes TARGET "${module}" PROPERTY INTERFACE_INCLUDE_DIRECTORIES)
    set(args "")
    foreach(include IN LISTS includes)
      string(APPEND args "-I\"${include}\"\n")
    endforeach()
    file(WRITE "${work}.args" "${args}")
    add_custom_command(
      OUTPUT "${hierarchy}"
      COMMAND VTK::WrapHierarchy "@${work}.args" -o "${hierarchy}" "${work}.data"
        "@${work}.depends.args"
      DEPENDS ${depends_files} "${work}.data"
      COMMENT "Writing the wrap hierarchy of ${module}"
      VERBATIM)
    list(APPEND outputs "${hierarchy}")
  endforeach()
  add_custom_target("${H_TARGET}" DEPENDS ${outputs})
endfunction()
