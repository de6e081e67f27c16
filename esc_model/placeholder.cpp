// Replaced by the ESC implementation.
