# The session proxy's haptic-parameter properties, generated from the one table of haptic
# parameters (Logic/Haptics/vtouchHapticParameters.def) at configure time, so that names,
# defaults, ranges and meanings in the server-manager XML cannot drift from the C++ struct.
#
# vtouch_haptic_parameter_properties(<def file> <output variable>) sets the variable to the XML of
# one property per row: a DoubleVectorProperty with a DoubleRangeDomain (Real), or an
# IntVectorProperty with a BooleanDomain (Boolean), an IntRangeDomain (Integer) or an
# EnumerationDomain (Choice). Each calls SetHapticParameter("<Name>", value) through ParaView's
# initial_string (vtkSIVectorProperty), which validates against the same table.

function(_vtouch_xml_escape text out)
  string(REPLACE "&" "&amp;" text "${text}")
  string(REPLACE "<" "&lt;" text "${text}")
  string(REPLACE ">" "&gt;" text "${text}")
  set(${out} "${text}" PARENT_SCOPE)
endfunction()

# Splits the body of one row into its 12 fields (strings unquoted).
function(_vtouch_parameter_fields body out)
  string(REGEX MATCHALL "\"[^\"]*\"|[^,\"]+" tokens "${body}")
  set(fields)
  foreach(token IN LISTS tokens)
    string(STRIP "${token}" token)
    if(token STREQUAL "")
      continue()
    endif()
    if(token MATCHES "^\"(.*)\"$")
      set(token "${CMAKE_MATCH_1}")
      if(token STREQUAL "")
        set(token "-") # an empty string would vanish from the list
      endif()
    endif()
    list(APPEND fields "${token}")
  endforeach()
  set(${out} "${fields}" PARENT_SCOPE)
endfunction()

function(vtouch_haptic_parameter_properties def_file out_var)
  file(STRINGS "${def_file}" rows REGEX "^VTOUCH_HAPTIC_PARAMETER\\(")
  set(xml "")
  set(count 0)
  foreach(row IN LISTS rows)
    if(NOT row MATCHES "^VTOUCH_HAPTIC_PARAMETER\\((.*)\\)$")
      message(FATAL_ERROR "${def_file}: a row must stand on one line: ${row}")
    endif()
    _vtouch_parameter_fields("${CMAKE_MATCH_1}" fields)
    list(LENGTH fields n)
    if(NOT n EQUAL 12)
      message(FATAL_ERROR "${def_file}: ${n} fields instead of 12 (no ';' or '\"' inside strings): ${row}")
    endif()
    list(GET fields 2 name)
    list(GET fields 3 kind)
    list(GET fields 4 label)
    list(GET fields 5 unit)
    list(GET fields 6 default)
    list(GET fields 7 minimum)
    list(GET fields 8 maximum)
    list(GET fields 9 choices)
    list(GET fields 10 meaning)
    list(GET fields 11 laws)
    if(unit STREQUAL "-")
      set(unit_text "")
      set(label_text "${label}")
    else()
      set(unit_text " ${unit}")
      set(label_text "${label} (${unit})")
    endif()
    set(laws_text "")
    if(NOT laws STREQUAL "-")
      string(REPLACE "|" ", " laws_text "${laws}")
      set(laws_text " Acts on the force laws: ${laws_text}.")
    endif()
    _vtouch_xml_escape("${label_text}: ${meaning} Default ${default}${unit_text}, range [${minimum}, ${maximum}]${unit_text}.${laws_text}" doc)
    set(head "name=\"${name}\" command=\"SetHapticParameter\" initial_string=\"${name}\" number_of_elements=\"1\" default_values=\"${default}\"")
    if(kind STREQUAL "Real")
      string(APPEND xml
        "      <DoubleVectorProperty ${head}>\n"
        "        <DoubleRangeDomain name=\"range\" min=\"${minimum}\" max=\"${maximum}\" />\n"
        "        <Documentation>${doc}</Documentation>\n"
        "      </DoubleVectorProperty>\n")
    elseif(kind STREQUAL "Boolean")
      string(APPEND xml
        "      <IntVectorProperty ${head}>\n"
        "        <BooleanDomain name=\"bool\" />\n"
        "        <Documentation>${doc}</Documentation>\n"
        "      </IntVectorProperty>\n")
    elseif(kind STREQUAL "Integer")
      string(APPEND xml
        "      <IntVectorProperty ${head}>\n"
        "        <IntRangeDomain name=\"range\" min=\"${minimum}\" max=\"${maximum}\" />\n"
        "        <Documentation>${doc}</Documentation>\n"
        "      </IntVectorProperty>\n")
    elseif(kind STREQUAL "Choice")
      string(REPLACE "|" ";" entries "${choices}")
      set(value ${minimum})
      set(entry_xml "")
      foreach(entry IN LISTS entries)
        _vtouch_xml_escape("${entry}" entry)
        string(APPEND entry_xml "          <Entry value=\"${value}\" text=\"${entry}\" />\n")
        math(EXPR value "${value} + 1")
      endforeach()
      math(EXPR last "${value} - 1")
      if(NOT last EQUAL maximum)
        message(FATAL_ERROR "${def_file}: ${name} lists the choices ${minimum}..${last}, not ${minimum}..${maximum}")
      endif()
      string(APPEND xml
        "      <IntVectorProperty ${head}>\n"
        "        <EnumerationDomain name=\"enum\">\n"
        "${entry_xml}"
        "        </EnumerationDomain>\n"
        "        <Documentation>${doc}</Documentation>\n"
        "      </IntVectorProperty>\n")
    else()
      message(FATAL_ERROR "${def_file}: ${name}: unknown kind '${kind}' (Real, Boolean, Integer, Choice)")
    endif()
    math(EXPR count "${count} + 1")
  endforeach()
  if(count EQUAL 0)
    message(FATAL_ERROR "${def_file}: no VTOUCH_HAPTIC_PARAMETER rows")
  endif()
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS "${def_file}")
  set(${out_var} "${xml}" PARENT_SCOPE)
endfunction()
