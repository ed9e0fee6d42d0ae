#pragma once
// Every pose source the Localizer can run, made from the setup: one line per source in
// source_registry.cpp. A source whose landmarks the map does not hold is not made.

#include <memory>
#include <vector>

#include "algo/pipeline/localizer_setup.hpp"
#include "algo/source/pose_source.hpp"

namespace irloc {

// Throws std::invalid_argument (start-up) for a map or config a source cannot use.
std::vector<std::unique_ptr<PoseSource>> make_pose_sources(const LocalizerSetup& setup, const SourceSetup& common);

}  // namespace irloc
