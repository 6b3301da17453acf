"""Tables on disk: saved tables and their checks, safe .npz reading, atomic writes, folders of
mapped arrays.
"""
