"""The core every layer reads: errors, validation, the design keys' schema, reports, atomic files, graphs.

It imports no other layer of the package (``.importlinter``); what the schema must
know of the layers above (their valid values, their checks) they register into it.
"""
