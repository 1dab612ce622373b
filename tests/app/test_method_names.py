"""The command line offers the force methods by name without importing them (issue 42 item
7): its static list is the methods' own."""
from mechreport.forces import METHODS
from mechreport.quantities import METHOD_NAMES


def test_the_static_method_names_are_the_methods():
    assert METHOD_NAMES == tuple(METHODS)
