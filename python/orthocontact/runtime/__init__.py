"""How a command lives as processes and folders, below every other layer:
locked and temporary folders (folders, temp: a killed command's scratch goes
with the next command), the worker bound (workers), worker processes that
ignore Ctrl-C and end with their parent, and a pool that forks them safely
(processes), a folder's content replaced in one step (swap), and the
command's interrupts: Ctrl-C, SIGINT and SIGTERM end it as interrupted, but
not once it commits its results (interrupts)."""
from .folders import LOCK, locked_folder
from .interrupts import (
    hold_interrupts,
    install_signal_handlers,
    interrupted,
    quiet_interrupts,
    quiet_leftovers,
    results_written,
    written,
)
from .processes import end_with_parent, process_pool, signals_held, stop_pool
from .swap import UNSUPPORTED, can_exchange, exchange, link_tree, merge_into, prune_empty
from .temp import TEMP_ENV, remove_unzipped, temp_folder, unzipped
from .workers import check_workers, default_workers

__all__ = ["LOCK", "locked_folder", "hold_interrupts", "install_signal_handlers", "interrupted",
           "quiet_interrupts", "quiet_leftovers", "results_written", "written", "end_with_parent",
           "process_pool", "signals_held", "stop_pool", "UNSUPPORTED", "can_exchange", "exchange",
           "link_tree", "merge_into", "prune_empty", "TEMP_ENV", "remove_unzipped", "temp_folder",
           "unzipped", "check_workers", "default_workers"]
