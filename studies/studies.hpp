// The experiments: hsr compare (every algorithm against the exact reference), hsr sweep
// (one algorithm's accuracy against time over its knobs) and hsr study (a published
// experiment reproduced), each built on the pipeline (pipeline/pipeline.hpp). Each
// validates all of its input before doing any work, throws InputError for bad input (the
// command line prints it as one line and exits 2), and writes its output files only when
// all of them are complete.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace hsr::studies {

struct CompareOptions {
  std::vector<std::string> scenes;  // none: the built-in default study
  std::string algorithms;           // "a,b:knob=v,..." ; empty: every surface algorithm
  int repeat = 3;
  int threads = 0;
  std::string size;
  std::string out = "out/compare";
  bool wide = false;  // print every column (default: the six a reader compares first)
};
int compare(const CompareOptions& options);

struct SweepOptions {
  std::string scene;
  std::string algorithm = "zbuffer";
  std::string variant;             // fixed for every configuration
  std::vector<std::string> knobs;  // NAME=v1,v2,...; NAME "size" sweeps the resolution
  std::string scale;               // "", "triangles" or "pixels"
  int repeat = 3;
  int threads = 0;
  std::string size;
  std::string out = "out/sweep";
  bool wide = false;  // print every column (default: the six a reader compares first)
};
int sweep(const SweepOptions& options);

struct StudyOptions {
  std::string name;    // "culling-combos", one of the occlusion studies, "effects" or "shadow-map"
  std::string scenes;  // a subset of the study's scenes, "cube,counters"; empty: all four
  int frames = 0;      // 0: the study's own default
  int errorFrames = 4; // frames whose images are compared with the exact reference
  int threads = 1;
  std::string size;
  std::string out;     // "": out/study/NAME
  std::string shard;   // occlusion-queries: "K/N", this run's share of the walk; "": all of it
  std::vector<std::string> merge;  // occlusion-queries: shard folders to join instead of walking
};
int study(const StudyOptions& options);
// Where a study writes: --out, or out/study/NAME.
std::filesystem::path studyFolder(const StudyOptions& options);
// The occlusion studies (occlusion_studies.cpp), into `folder`.
int occlusionStudy(const StudyOptions& options, const std::filesystem::path& folder);
// occlusion-queries (occlusion_queries_study.cpp), into `folder`; its --shard and --merge
// checked first (InputError), before the folder is made.
void checkOcclusionQueriesOptions(const StudyOptions& options);
int occlusionQueriesStudy(const StudyOptions& options, const std::filesystem::path& folder);
// indoor (indoor_study.cpp): cells, portals and visible sets against occlusion culling.
int indoorStudy(const StudyOptions& options, const std::filesystem::path& folder);
// The effects studies (effects_studies.cpp), into `folder`.
int effectsStudy(const StudyOptions& options, const std::filesystem::path& folder);

}  // namespace hsr::studies
