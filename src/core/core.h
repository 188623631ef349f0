/* The plumbing the tools share, not part of the product's API: output files
 * and folders that appear whole or not at all, JSON documents written that
 * way, input files read only when regular and of a bounded size, the
 * progress bar, the records plugins allocate, the temporaries a signal
 * removes (temp_files.h), and backends loaded at their first use
 * (backend_library.h). This is src/core's
 * interface: other folders include this header, not the ones it gathers
 * (one per concept). */
#ifndef CELADON_CORE_H
#define CELADON_CORE_H

#include "core/atomic_file.h"
#include "core/backend_library.h"
#include "core/folder.h"
#include "core/input_file.h"
#include "core/json_file.h"
#include "core/output_check.h"
#include "core/progress.h"
#include "core/record.h"
#include "core/temp_files.h"
#include "core/vector_clones.h"

#endif
