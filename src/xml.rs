//! modelDescription.xml written from the variable table. (placeholder; filled in by the FMU work)
