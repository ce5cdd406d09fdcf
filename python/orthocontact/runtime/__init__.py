"""How a command lives as processes and folders, below every other layer:
locked and temporary folders (folders, temp: a killed command's scratch goes
with the next command), the worker bound (workers), worker processes that
ignore Ctrl-C and end with their parent, and a pool that forks them safely
(processes), a folder's content replaced in one step (swap), and the
command's interrupts: Ctrl-C, SIGINT and SIGTERM end it as interrupted, but
not once it commits its results (interrupts)."""
