class SiloscopeError(Exception):
    """A file siloscope wrote cannot be read as it should: the message names the file, the field and the value."""
