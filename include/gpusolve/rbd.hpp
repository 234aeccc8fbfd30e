// Umbrella header of the rigid-body solver: World and everything it steps,
// and the writers of frames and statistics; the prebuilt Worlds' declarations
// where the program links gpusolve::worlds.
#pragma once

#include "gpusolve/rbd/io/csv_writer.hpp"
#include "gpusolve/rbd/io/json_writer.hpp"
#include "gpusolve/rbd/io/povray_writer.hpp"
#include "gpusolve/rbd/io/vtk_writer.hpp"
#include "gpusolve/rbd/prebuilt_worlds.hpp"
#include "gpusolve/rbd/world.hpp"
