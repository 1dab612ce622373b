"""The application: the command line (:mod:`.cli`, one module per command), output folders,
worker processes, progress and the process set-up. The only layer that prints, exits or
changes the process; everything below returns results or raises."""
