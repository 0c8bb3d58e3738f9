// A .pvti and its pieces are one run's output (FieldPieces.h): each records the run that wrote
// it, the reader refuses pieces of another run, and a write with fewer pieces removes those of
// the older output beyond the new count. What an interrupted or failing run leaves is tested by
// the faults tests (tests/faults/InterruptPieces.sh) and app.mpi.*.
#include "FieldPieces.h"
#include "FieldTestFiles.h"
#include "KnownFieldFiles.h"
#include "SupportRun.h"

#include <gtest/gtest.h>
#include <vtkDummyCommunicator.h>
#include <vtkDummyController.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkXMLImageDataWriter.h>

#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

namespace
{

using namespace cloudvis::support;
using namespace cloudvis::test;

// Every write is a run of its own, recorded in the .pvti and in each of its pieces.
TEST(ParallelFiles, TheParallelFileAndEachPieceRecordTheirRun)
{
  TemporaryDirectory dir;
  const auto field = RotatedField();
  cloudvis::WriteFieldPieces(field, dir.File("a.pvti"), 3);
  const std::string run = RecordedRun(dir.File("a.pvti"));
  EXPECT_EQ(run.size(), 32u);
  EXPECT_EQ(run.find_first_not_of("0123456789abcdef"), std::string::npos) << run;
  for (int p = 0; p < 3; ++p)
  {
    EXPECT_EQ(RecordedRun(cloudvis::PieceFileName(dir.File("a.pvti"), p)), run) << p;
  }
  cloudvis::WriteFieldPieces(field, dir.File("a.pvti"), 3);
  EXPECT_NE(RecordedRun(dir.File("a.pvti")), run) << "two writes recorded the same run";
  EXPECT_EQ(dir.Files(), (std::vector<std::string>{ "a.pvti", "a_0.vti", "a_1.vti", "a_2.vti" }))
    << "a temporary was left";
}

// A piece of another run among a .pvti's pieces (what a run killed between its renames, or two
// runs writing the same .pvti at once, leave) is refused, naming the piece and both runs; so are
// pieces of two runs under a .pvti that records none (VTK's, or an older cloudvis's), and a
// piece recording no run under one that does. VTK itself reads all of these without complaint.
TEST(ParallelFiles, PiecesOfAnotherRunAreRefused)
{
  TemporaryDirectory dir;
  const auto field = RotatedField();
  const std::string path = dir.File("a.pvti");
  cloudvis::WriteFieldPieces(field, path, 2);
  cloudvis::WriteFieldPieces(field, dir.File("b.pvti"), 2);
  const std::string a1 = ReadText(dir.File("a_1.vti"));
  WriteText(dir.File("a_1.vti"), ReadText(dir.File("b_1.vti")));
  std::string error = ErrorOf([&] { cloudvis::ReadField(path); });
  EXPECT_NE(
    error.find("a.pvti: piece 1 (a_1.vti) was written by run " + RecordedRun(dir.File("b.pvti")) +
      ", the .pvti by run " + RecordedRun(path) + ": the pieces of two generate runs are mixed"),
    std::string::npos)
    << error;

  // The .pvti records no run: its pieces must still agree.
  std::string text = ReadText(path);
  const auto attribute = text.find(std::string(" ") + cloudvis::PieceRunAttribute + "=");
  text.erase(attribute, text.find('"', text.find('"', attribute) + 1) + 1 - attribute);
  WriteText(path, text);
  error = ErrorOf([&] { cloudvis::ReadField(path); });
  EXPECT_NE(error.find("piece 1 (a_1.vti) was written by run " + RecordedRun(dir.File("b.pvti")) +
              ", piece 0 (a_0.vti) by run " + RecordedRun(dir.File("a_0.vti"))),
    std::string::npos)
    << error;
  WriteText(dir.File("a_1.vti"), a1);
  ExpectSameField(field, cloudvis::ReadField(path));

  // A piece VTK wrote (no run) under a .pvti that records one.
  cloudvis::WriteFieldPieces(field, path, 1);
  vtkNew<vtkXMLImageDataWriter> writer;
  writer->SetInputData(field);
  writer->SetFileName(dir.File("a_0.vti").c_str());
  ASSERT_EQ(writer->Write(), 1);
  error = ErrorOf([&] { cloudvis::ReadField(path); });
  EXPECT_NE(error.find("piece 0 (a_0.vti) records no run, the .pvti by run"), std::string::npos)
    << error;
}

// Written again with fewer pieces, a .pvti's pieces beyond the new count are removed: those it
// named (even written by VTK) and any cloudvis piece of that name; other files are kept.
TEST(ParallelFiles, PiecesOfAnOlderOutputBeyondTheNewCountAreRemoved)
{
  TemporaryDirectory dir;
  const auto field = RotatedField();
  const std::string path = dir.File("p.pvti");
  cloudvis::WriteFieldPieces(field, path, 5);
  dir.Write("p_9.vti", "not a piece");
  dir.Write("p_x.vti", "not a piece either");
  cloudvis::WriteFieldPieces(field, dir.File("q.pvti"), 8);
  std::filesystem::rename(dir.File("q_7.vti"), dir.File("p_7.vti")); // a stray cloudvis piece
  for (const char* name :
    { "q.pvti", "q_0.vti", "q_1.vti", "q_2.vti", "q_3.vti", "q_4.vti", "q_5.vti", "q_6.vti" })
  {
    std::filesystem::remove(dir.File(name));
  }
  cloudvis::WriteFieldPieces(field, path, 2);
  EXPECT_EQ(dir.Files(),
    (std::vector<std::string>{ "p.pvti", "p_0.vti", "p_1.vti", "p_9.vti", "p_x.vti" }));
  ExpectSameField(field, cloudvis::ReadField(path));
}

// Process 0 of two, in this process: the collective calls RunAgreed makes are recorded and
// answered as the one process taking part would see them (the lowest failing rank is its own).
class RecordingCommunicator : public vtkDummyCommunicator
{
public:
  static RecordingCommunicator* New();
  vtkTypeMacro(RecordingCommunicator, vtkDummyCommunicator);
  int Votes = 0;
  std::string Broadcast; // the characters process 0 sent to the others
  RecordingCommunicator()
  {
    this->NumberOfProcesses = 2;
    this->LocalProcessId = 0;
  }
  int AllReduceVoidArray(const void* send,
    void* receive,
    vtkIdType length,
    int type,
    int operation) override
  {
    ++this->Votes;
    EXPECT_EQ(type, VTK_INT);
    EXPECT_EQ(operation, vtkCommunicator::MIN_OP);
    std::memcpy(receive, send, std::size_t(length) * sizeof(int));
    return 1;
  }
  int BroadcastVoidArray(void* data, vtkIdType length, int type, int source) override
  {
    EXPECT_EQ(source, 0);
    if (type == VTK_CHAR)
    {
      this->Broadcast.assign(static_cast<const char*>(data), std::size_t(length));
    }
    return 1;
  }
};
vtkStandardNewMacro(RecordingCommunicator);

// Whatever a step throws, not only a std::exception, the process still takes part in the vote
// (else the other processes would wait for it for ever), tells them it failed, and then rethrows
// its own exception.
TEST(ParallelFiles, AStepThrowingAnythingStillTakesPartInTheVote)
{
  vtkNew<RecordingCommunicator> communicator;
  vtkNew<vtkDummyController> controller;
  controller->SetCommunicator(communicator);
  ASSERT_EQ(controller->GetNumberOfProcesses(), 2);
  struct NotAStandardException
  {
  };
  EXPECT_THROW(
    cloudvis::RunAgreed(controller, [] { throw NotAStandardException{}; }), NotAStandardException);
  EXPECT_EQ(communicator->Votes, 1);
  EXPECT_EQ(communicator->Broadcast, "an unknown error");
}

} // namespace
