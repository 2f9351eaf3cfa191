// An empty translation unit: the shared objects topple_<layer>_link_check (src/CMakeLists.txt) are made of one layer's
// library, whole, and the layers below it; this file only gives CMake a source to build them from.
