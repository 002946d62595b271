# The fuzz targets, one line each (the function is in fuzz/CMakeLists.txt;
# scripts/fuzz.sh reads this file too, so keep every call on one line).
# Adding a reader: write fuzz/<name>_fuzzer.cc (LLVMFuzzerTestOneInput, on the
# checks of fuzz/fuzz_checks.h), put seeds in fuzz/corpus_<name>/, add a line.
ccma_fuzz_target(NAME loader SOURCE loader_fuzzer.cc CORPUS corpus_loader DICT loader.dict LAYERS core formats)
ccma_fuzz_target(NAME obstacles SOURCE obstacles_fuzzer.cc CORPUS corpus_obstacles DICT obstacles.dict LAYERS core formats)
ccma_fuzz_target(NAME waypoints SOURCE waypoints_fuzzer.cc CORPUS corpus_waypoints DICT waypoints.dict LAYERS core formats)
ccma_fuzz_target(NAME trajectory_csv SOURCE trajectory_csv_fuzzer.cc CORPUS corpus_trajectory_csv DICT trajectory_csv.dict MAX_LEN 32768 LAYERS core formats SOURCES viewer/csv_reader.cc viewer/view_frames.cc)
ccma_fuzz_target(NAME urdf SOURCE urdf_fuzzer.cc CORPUS corpus_urdf LAYERS analyses robot_files)
ccma_fuzz_target(NAME sdformat SOURCE sdformat_fuzzer.cc CORPUS corpus_sdformat LAYERS analyses robot_files)
ccma_fuzz_target(NAME mjcf SOURCE mjcf_fuzzer.cc CORPUS corpus_mjcf LAYERS analyses robot_files)
ccma_fuzz_target(NAME stl SOURCE stl_fuzzer.cc CORPUS corpus_stl LAYERS core formats SOURCES viewer/stl.cc)
ccma_fuzz_target(NAME workspace_tile SOURCE workspace_tile_fuzzer.cc CORPUS corpus_workspace_tile LAYERS analyses SOURCES apps/workspace_tile_file.cc)
ccma_fuzz_target(NAME store_manifest SOURCE store_manifest_fuzzer.cc CORPUS corpus_store_manifest LAYERS analyses SOURCES apps/workspace_store_manifest.cc apps/workspace_tile_file.cc LINK nlohmann_json::nlohmann_json)
