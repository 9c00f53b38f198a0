"""A stand-in for the RoboDK Python package (``robodk``), for roprec's tests only.

It implements exactly the calls roprec's RoboDK app (plugin/robodk/roprec_compensate_program.py)
makes, with the signatures of the RoboDK API (robodk.robolink, robodk.robomath), against an
in-memory station instead of a running RoboDK. See robolink.py.
"""
