"""The panic entry points of `core` that a firmware binary's code may branch to: `panic_fmt`,
`panic_bounds_check`, `slice_index_fail`, `expect`/`unwrap` failures, assertion and division
panics, and the panic handler. Shared by scripts/prove-no-panic.sh (which lists who branches to
them) and scripts/lib/stack_bound.py (which cuts calls into them).
"""

import re

ENTRY = re.compile(
    r"(core::panicking::[^>]+|core::slice::index::slice_index_fail|core::option::expect_failed|"
    r"core::option::unwrap_failed|core::result::unwrap_failed|__rustc::rust_begin_unwind)"
)
