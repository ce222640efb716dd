# SPDX-License-Identifier: GPL-3.0-or-later
# Keeps a generated block of a Markdown document equal to what sonargrid-cli prints.
#
# The block sits between the lines
#   <!-- BEGIN GENERATED: sonargrid-cli ARGS -->
#   <!-- END GENERATED -->
# and holds exactly the output of `sonargrid-cli ARGS`.
#
#   Check (ctest docs_models_in_sync):
#     cmake -DCLI=path/to/sonargrid-cli -DDOC=docs/models.md -P tests/cli/check_generated_doc.cmake
#   Rewrite the block in place:
#     cmake -DCLI=path/to/sonargrid-cli -DDOC=docs/models.md -DWRITE=1 -P tests/cli/check_generated_doc.cmake
#
# ARGS defaults to "models;--markdown" (a CMake list).

cmake_minimum_required(VERSION 3.25)

foreach(var CLI DOC)
  if(NOT DEFINED ${var} OR "${${var}}" STREQUAL "")
    message(FATAL_ERROR "check_generated_doc.cmake: pass -D${var}=... (see the comment at the top)")
  endif()
endforeach()
if(NOT DEFINED ARGS)
  set(ARGS models --markdown)
endif()
list(JOIN ARGS " " args_text)

set(begin_marker "<!-- BEGIN GENERATED: sonargrid-cli ${args_text} -->\n")
set(end_marker "<!-- END GENERATED -->")
set(regenerate "cmake -DCLI=${CLI} -DDOC=${DOC} -DWRITE=1 -P ${CMAKE_CURRENT_LIST_FILE}")

execute_process(COMMAND "${CLI}" ${ARGS}
                OUTPUT_VARIABLE generated
                ERROR_VARIABLE cli_error
                RESULT_VARIABLE cli_status)
if(NOT cli_status EQUAL 0)
  message(FATAL_ERROR "`sonargrid-cli ${args_text}` failed (${cli_status}): ${cli_error}")
endif()
if(generated STREQUAL "")
  message(FATAL_ERROR "`sonargrid-cli ${args_text}` printed nothing")
endif()

if(NOT EXISTS "${DOC}")
  message(FATAL_ERROR "${DOC} does not exist")
endif()
file(READ "${DOC}" doc)
# A checkout with CRLF line ends still compares equal.
string(REPLACE "\r\n" "\n" doc "${doc}")

string(FIND "${doc}" "${begin_marker}" begin_at)
if(begin_at EQUAL -1)
  message(FATAL_ERROR "${DOC} has no line `<!-- BEGIN GENERATED: sonargrid-cli ${args_text} -->`")
endif()
string(LENGTH "${begin_marker}" begin_length)
math(EXPR block_at "${begin_at} + ${begin_length}")
string(SUBSTRING "${doc}" ${block_at} -1 rest)
string(FIND "${rest}" "${end_marker}" block_length)
if(block_length EQUAL -1)
  message(FATAL_ERROR "${DOC} has no line `${end_marker}` after its BEGIN GENERATED marker")
endif()
string(SUBSTRING "${rest}" 0 ${block_length} current)

if(WRITE)
  if(current STREQUAL generated)
    message(STATUS "${DOC}: generated block already up to date")
    return()
  endif()
  string(SUBSTRING "${doc}" 0 ${block_at} head)
  string(SUBSTRING "${rest}" ${block_length} -1 tail)
  file(WRITE "${DOC}" "${head}${generated}${tail}")
  message(STATUS "${DOC}: generated block rewritten from `sonargrid-cli ${args_text}`")
  return()
endif()

if(NOT current STREQUAL generated)
  # Show what differs when a diff tool is at hand, on stdout as it comes (a FATAL_ERROR message
  # would rewrap the lines), through two scratch files in the working directory.
  set(see_diff "")
  find_program(DIFF_PROGRAM diff)
  if(DIFF_PROGRAM)
    get_filename_component(doc_name "${DOC}" NAME_WE)
    set(in_doc "${CMAKE_CURRENT_BINARY_DIR}/${doc_name}.in-doc.md")
    set(from_cli "${CMAKE_CURRENT_BINARY_DIR}/${doc_name}.from-cli.md")
    file(WRITE "${in_doc}" "${current}")
    file(WRITE "${from_cli}" "${generated}")
    execute_process(COMMAND "${DIFF_PROGRAM}" -u "${in_doc}" "${from_cli}")
    file(REMOVE "${in_doc}" "${from_cli}")
    set(see_diff " (diff above: - in the document, + from the CLI)")
  endif()
  message(FATAL_ERROR
    "${DOC}: the block between the GENERATED markers differs from `sonargrid-cli ${args_text}`"
    "${see_diff}. Do not edit that block by hand: change the parameter declarations in"
    " core/sonargrid/models/ or core/sonargrid/rules/ (or the generator in"
    " app/cli/command_models.cpp), then regenerate the block with\n"
    "  ${regenerate}\n")
endif()
message(STATUS "${DOC}: generated block matches `sonargrid-cli ${args_text}`")
