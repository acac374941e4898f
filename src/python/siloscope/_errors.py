class SiloscopeError(ValueError):
    """A value siloscope was given or a file it wrote cannot be used as it should: the message names the file,
    the field and the value. A ValueError, so code that catches bad values catches it."""
