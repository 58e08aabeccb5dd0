// Umbrella header of the common library.
#pragma once

#include "common/config.h"
#include "common/csv_table.h"
#include "common/enum_names.h"
#include "common/error.h"
#include "common/hdf5_file.h"
#include "common/provenance.h"
#include "common/state_measures.h"
#include "common/stopwatch.h"
#include "common/time_series.h"
