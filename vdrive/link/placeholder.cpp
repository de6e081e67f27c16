// Replaced by the link implementations.
