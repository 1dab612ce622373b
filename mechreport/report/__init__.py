"""Stage 6: rendering. Reads result models; never computes mechanics."""
